// Boundary conditions of a model: fixed and prescribed displacement components on node sets
// (functions of time and reference position) and nodal loads, resolved to nodal dofs once and
// evaluated per step for the solver.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <unordered_map>
#include <vector>

#include "fem/dof_map.hpp"
#include "mesh/mesh.hpp"
#include "model/time_function.hpp"
#include "spec/problem_spec.hpp"

namespace cc {

class BoundaryConditions {
 public:
  // Resolves the deck's fix, prescribe and load items against the mesh's node sets. Throws
  // InputError for unknown sets, bad expressions and contradicting conditions on one dof.
  void build(const ProblemSpec& spec, const Mesh& mesh);

  // Dofs (3 * node + component) carrying a Dirichlet condition.
  std::vector<bool> constrainedDofs(int numNodes) const;
  // Values of the prescribed dofs in DofMap::prescribedDofs() order.
  void prescribedValues(double t, const DofMap& dofs, const Eigen::Matrix3Xd& reference,
                        Eigen::VectorXd& values) const;
  void externalForces(double t, const Eigen::Matrix3Xd& reference, Eigen::VectorXd& force) const;

 private:
  struct Condition {
    int function = -1;  // index into functions_, -1: fixed at zero
    SourceLocation where;
  };
  struct NodalLoad {
    int dof = 0;
    int function = 0;
    double scale = 1;  // 1 / (nodes of the set) for `total` loads
  };
  int addFunction(const FunctionSpec& spec);
  void constrain(int dof, Condition condition, const std::string& set, const char* component);

  std::vector<std::unique_ptr<ScalarFunction>> functions_;
  std::unordered_map<int, Condition> conditions_;  // by dof
  std::vector<NodalLoad> loads_;
};

// The node set `name` of the mesh, or InputError at `where` with a suggestion.
const NodeSet& requireNodeSet(const Mesh& mesh, const std::string& name,
                              const SourceLocation& where, const char* purpose);

}  // namespace cc
