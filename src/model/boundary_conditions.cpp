// Boundary conditions: resolution of fix/prescribe/load to dofs and their evaluation in time.
#include "model/boundary_conditions.hpp"

#include <fmt/format.h>

#include "common/errors.hpp"
#include "common/name_matching.hpp"

namespace cc {

namespace {
constexpr const char* kComponentNames[3] = {"ux", "uy", "uz"};
}  // namespace

const NodeSet& requireNodeSet(const Mesh& mesh, const std::string& name,
                              const SourceLocation& where, const char* purpose) {
  const auto it = mesh.nodeSets.find(name);
  if (it != mesh.nodeSets.end()) return it->second;
  std::vector<std::string> names;
  for (const auto& entry : mesh.nodeSets) names.push_back(entry.first);
  throw InputError(where, fmt::format("{}: the mesh has no group or node set '{}'{}", purpose, name,
                                      deck::didYouMean(name, names)));
}

int BoundaryConditions::addFunction(const FunctionSpec& spec) {
  functions_.push_back(makeFunction(spec));
  return static_cast<int>(functions_.size()) - 1;
}

void BoundaryConditions::constrain(int dof, Condition condition, const std::string& set,
                                   const char* component) {
  auto [it, inserted] = conditions_.try_emplace(dof, condition);
  if (inserted) return;
  const bool bothFixed = it->second.function < 0 && condition.function < 0;
  if (bothFixed) return;  // fixing a dof twice (sets sharing an edge) is harmless
  throw InputError(condition.where,
                   fmt::format("{} of a node in set '{}' already has a condition from {}; a dof "
                               "can be fixed or prescribed by one line only",
                               component, set, it->second.where.str()));
}

void BoundaryConditions::build(const ProblemSpec& spec, const Mesh& mesh) {
  for (const FixSpec& fix : spec.fixes) {
    const NodeSet& set = requireNodeSet(mesh, fix.set, fix.where, "fix");
    for (int c = 0; c < 3; ++c) {
      if (!fix.components[c]) continue;
      for (int node : set.nodes)
        constrain(3 * node + c, {-1, fix.where}, fix.set, kComponentNames[c]);
    }
  }
  for (const PrescribeSpec& prescribe : spec.prescribed) {
    const NodeSet& set = requireNodeSet(mesh, prescribe.set, prescribe.where, "prescribe");
    for (int c = 0; c < 3; ++c) {
      if (!prescribe.components[c]) continue;
      const int function = addFunction(*prescribe.components[c]);
      for (int node : set.nodes) {
        constrain(3 * node + c, {function, prescribe.where}, prescribe.set, kComponentNames[c]);
      }
    }
  }
  for (const LoadSpec& load : spec.loads) {
    const NodeSet& set = requireNodeSet(mesh, load.set, load.where, "load");
    const double scale = load.total ? 1.0 / static_cast<double>(set.nodes.size()) : 1.0;
    for (int c = 0; c < 3; ++c) {
      if (!load.components[c]) continue;
      const int function = addFunction(*load.components[c]);
      for (int node : set.nodes) loads_.push_back({3 * node + c, function, scale});
    }
  }
}

std::vector<bool> BoundaryConditions::constrainedDofs(int numNodes) const {
  std::vector<bool> constrained(3 * static_cast<std::size_t>(numNodes), false);
  for (const auto& [dof, condition] : conditions_) constrained[dof] = true;
  return constrained;
}

void BoundaryConditions::prescribedValues(double t, const DofMap& dofs,
                                          const Eigen::Matrix3Xd& reference,
                                          Eigen::VectorXd& values) const {
  values.setZero(dofs.numPrescribed());
  for (int p = 0; p < dofs.numPrescribed(); ++p) {
    const int dof = dofs.prescribedDofs()[p];
    const Condition& condition = conditions_.at(dof);
    if (condition.function >= 0) {
      values[p] = (*functions_[condition.function])(t, reference.col(dof / 3));
    }
  }
}

void BoundaryConditions::externalForces(double t, const Eigen::Matrix3Xd& reference,
                                        Eigen::VectorXd& force) const {
  force.setZero(3 * reference.cols());
  for (const NodalLoad& load : loads_) {
    force[load.dof] += load.scale * (*functions_[load.function])(t, reference.col(load.dof / 3));
  }
}

}  // namespace cc
