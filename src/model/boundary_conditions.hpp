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
  // InputError for unknown sets, bad expressions and contradicting conditions on one dof: two
  // conditions on a dof (overlapping sets, fix and prescribe) are accepted only if they give the
  // same value at every time checkedTimes() lists, else refused naming both deck lines.
  void build(const ProblemSpec& spec, const Mesh& mesh);

  // Dofs (3 * node + component) carrying a Dirichlet condition.
  std::vector<bool> constrainedDofs(int numNodes) const;
  // Values of the prescribed dofs in DofMap::prescribedDofs() order. The two conditions of every
  // doubly constrained dof are compared again at t (a cut-back can reach a time build() never
  // compared): InputError, as in build(), if they differ there.
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
  // A second condition on a dof that already has one, compared once all are known and again at
  // every time the run evaluates the conditions.
  struct Overlap {
    int dof = 0;
    Condition first;
    Condition second;
    std::string set;       // the second condition's set
    std::string nodeName;  // "gmsh node N", for the message
    double scale = 0;      // the largest |value| of both at the times build() compared
  };
  int addFunction(const FunctionSpec& spec);
  void constrain(int dof, Condition condition, const std::string& set);
  double conditionValue(const Condition& condition, double t, const Eigen::Vector3d& x) const;
  void checkOverlaps(const ProblemSpec& spec, const Mesh& mesh);
  void checkOverlapsAt(double t, const Eigen::Matrix3Xd& reference) const;
  [[noreturn]] void refuse(const Overlap& overlap, const Eigen::Vector3d& x, double t, double first,
                           double second) const;

  std::vector<std::unique_ptr<ScalarFunction>> functions_;
  std::unordered_map<int, Condition> conditions_;  // by dof
  // The overlaps checked at run time: one per pair of time-only conditions (the same at every
  // node), one per dof where a condition depends on the position.
  std::vector<Overlap> overlaps_;
  std::vector<NodalLoad> loads_;
};

// The times at which two conditions on one dof must agree: t = 0, every step time of the solve
// block's phases and every step's midpoint (where the first cut-back of a step lands with the
// default factor 0.5). A phase of more than `maxStepsPerPhase` steps is represented by that many
// evenly spaced steps and its end. Sorted, without repeats.
std::vector<double> checkedTimes(const std::vector<PhaseSpec>& phases, int maxStepsPerPhase);

// The node set `name` of the mesh, or InputError at `where` with a suggestion.
const NodeSet& requireNodeSet(const Mesh& mesh, const std::string& name,
                              const SourceLocation& where, const char* purpose);

}  // namespace cc
