// Boundary conditions: resolution of fix/prescribe/load to dofs, the rule for two conditions on
// one dof, and their evaluation in time.
#include "model/boundary_conditions.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "common/errors.hpp"
#include "common/name_matching.hpp"

namespace cc {

namespace {
constexpr const char* kComponentNames[3] = {"ux", "uy", "uz"};
// Two conditions agree when they differ by round-off only: expressions equal in exact arithmetic
// ("t/10" and "0.1*t") differ by a few units in the last place of the largest value they take.
constexpr double kAgreement = 1e3 * std::numeric_limits<double>::epsilon();
// Steps per phase at which time-only conditions are compared (one evaluation per time), and the
// evaluations spent on conditions that depend on the position (one per node and time, ~0.1 s of
// muParser); those see fewer steps per phase on large overlaps, never fewer than the minimum.
constexpr int kMaxCheckedStepsPerPhase = 10000;
constexpr int kMinCheckedStepsPerPhase = 16;
constexpr double kPositionEvaluationBudget = 2e6;

const char* conditionKeyword(int function) {
  return function < 0 ? "fix" : "prescribe";
}
}  // namespace

std::vector<double> checkedTimes(const std::vector<PhaseSpec>& phases, int maxStepsPerPhase) {
  std::vector<double> times{0.0};
  double phaseStart = 0;
  for (const PhaseSpec& phase : phases) {
    // Step k of a phase ends at phaseStart + k * dt, as LoadStepper computes it (bit for bit).
    const long long steps = phase.steps;
    if (steps <= 0) continue;
    const long long stride =
        std::max<long long>(1, (steps + maxStepsPerPhase - 1) / std::max(1, maxStepsPerPhase));
    for (long long k = stride;; k += stride) {
      const double end = static_cast<double>(std::min(k, steps));
      times.push_back(phaseStart + end * phase.dt);
      times.push_back(phaseStart + (end - 0.5) * phase.dt);
      if (k >= steps) break;
    }
    phaseStart = phaseStart + phase.steps * phase.dt;
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

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

void BoundaryConditions::constrain(int dof, Condition condition, const std::string& set) {
  auto [it, inserted] = conditions_.try_emplace(dof, condition);
  if (inserted) return;
  const bool bothFixed = it->second.function < 0 && condition.function < 0;
  if (bothFixed) return;  // fixing a dof twice (sets sharing an edge) is harmless
  // Judged once every condition is known (checkOverlaps); the first condition stays in force.
  overlaps_.push_back({dof, it->second, condition, set, {}, 0.0});
}

double BoundaryConditions::conditionValue(const Condition& condition, double t,
                                          const Eigen::Vector3d& x) const {
  return condition.function < 0 ? 0.0 : (*functions_[condition.function])(t, x);
}

// The message of two conditions that differ at t, at the later line.
void BoundaryConditions::refuse(const Overlap& overlap, const Eigen::Vector3d& x, double t,
                                double first, double second) const {
  throw InputError(
      overlap.second.where,
      fmt::format("{} '{}': {} of {} at ({}, {}, {}) is also {} by the line at {}, which "
                  "gives {} at t = {} where this line gives {}; two conditions on one dof "
                  "must give the same value at every time the run evaluates them: t = 0, every "
                  "step end and step midpoint (compared before the run) and any other time a "
                  "cut-back reaches (compared there; a fixed dof: 0)",
                  conditionKeyword(overlap.second.function), overlap.set,
                  kComponentNames[overlap.dof % 3], overlap.nodeName, x[0], x[1], x[2],
                  overlap.first.function < 0 ? "fixed" : "prescribed", overlap.first.where.str(),
                  first, t, second));
}

// One rule for every pair of conditions on a dof (fix + fix, fix + prescribe 0, the same
// prescribed motion from overlapping sets): the same value at every time the run can ask for,
// else refused. Before, fix + fix was accepted and fix + `prescribe ... 0` refused. Compared here
// at the times every run reaches, so that `check` refuses the deck; the overlaps kept are
// compared again at each time the run evaluates (checkOverlapsAt): a cut-back by another factor
// than 0.5, or a second one, lands on times not listed here.
void BoundaryConditions::checkOverlaps(const ProblemSpec& spec, const Mesh& mesh) {
  if (overlaps_.empty()) return;
  const auto dependsOnPosition = [&](const Condition& condition) {
    return condition.function >= 0 && functions_[condition.function]->dependsOnPosition();
  };
  std::size_t positional = 0;
  for (const Overlap& overlap : overlaps_) {
    if (dependsOnPosition(overlap.first) || dependsOnPosition(overlap.second)) ++positional;
  }
  const std::vector<double> timeOnlyTimes = checkedTimes(spec.phases, kMaxCheckedStepsPerPhase);
  std::vector<double> positionTimes;
  if (positional > 0) {
    const double phases = static_cast<double>(std::max<std::size_t>(1, spec.phases.size()));
    // Two conditions, and a step end and a midpoint per checked step.
    const double steps =
        kPositionEvaluationBudget / (4.0 * static_cast<double>(positional) * phases);
    positionTimes = checkedTimes(
        spec.phases, static_cast<int>(std::clamp(steps, double{kMinCheckedStepsPerPhase},
                                                 double{kMaxCheckedStepsPerPhase})));
  }
  std::set<std::pair<int, int>> comparedPairs;  // time-only pairs give the same at every node
  std::vector<Overlap> kept;
  std::vector<double> first;
  std::vector<double> second;
  for (Overlap& overlap : overlaps_) {
    const bool position = dependsOnPosition(overlap.first) || dependsOnPosition(overlap.second);
    if (!position &&
        !comparedPairs.insert({overlap.first.function, overlap.second.function}).second) {
      continue;
    }
    const std::vector<double>& times = position ? positionTimes : timeOnlyTimes;
    const int node = overlap.dof / 3;
    const Eigen::Vector3d x = mesh.coordinates.col(node);
    overlap.nodeName = mesh.nodeName(node);
    first.resize(times.size());
    second.resize(times.size());
    double scale = 0;
    for (std::size_t i = 0; i < times.size(); ++i) {
      first[i] = conditionValue(overlap.first, times[i], x);
      second[i] = conditionValue(overlap.second, times[i], x);
      scale = std::max({scale, std::abs(first[i]), std::abs(second[i])});
    }
    for (std::size_t i = 0; i < times.size(); ++i) {
      if (std::abs(first[i] - second[i]) > kAgreement * scale) {
        refuse(overlap, x, times[i], first[i], second[i]);
      }
    }
    overlap.scale = scale;
    kept.push_back(std::move(overlap));
  }
  overlaps_ = std::move(kept);
}

// The same comparison at a time the run evaluates. Round-off is measured against the largest
// value the two took at the compared times as well (a motion through 0 at t differs there by a
// few ulps of its amplitude, not of its value at t). Costs at most one more evaluation per
// prescribed dof and time, as many as prescribedValues() itself.
void BoundaryConditions::checkOverlapsAt(double t, const Eigen::Matrix3Xd& reference) const {
  for (const Overlap& overlap : overlaps_) {
    const Eigen::Vector3d x = reference.col(overlap.dof / 3);
    const double first = conditionValue(overlap.first, t, x);
    const double second = conditionValue(overlap.second, t, x);
    const double scale = std::max({overlap.scale, std::abs(first), std::abs(second)});
    if (std::abs(first - second) > kAgreement * scale) refuse(overlap, x, t, first, second);
  }
}

void BoundaryConditions::build(const ProblemSpec& spec, const Mesh& mesh) {
  for (const FixSpec& fix : spec.fixes) {
    const NodeSet& set = requireNodeSet(mesh, fix.set, fix.where, "fix");
    for (int c = 0; c < 3; ++c) {
      if (!fix.components[c]) continue;
      for (int node : set.nodes) constrain(3 * node + c, {-1, fix.where}, fix.set);
    }
  }
  for (const PrescribeSpec& prescribe : spec.prescribed) {
    const NodeSet& set = requireNodeSet(mesh, prescribe.set, prescribe.where, "prescribe");
    for (int c = 0; c < 3; ++c) {
      if (!prescribe.components[c]) continue;
      const int function = addFunction(*prescribe.components[c]);
      for (int node : set.nodes) {
        constrain(3 * node + c, {function, prescribe.where}, prescribe.set);
      }
    }
  }
  checkOverlaps(spec, mesh);
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
  checkOverlapsAt(t, reference);
}

void BoundaryConditions::externalForces(double t, const Eigen::Matrix3Xd& reference,
                                        Eigen::VectorXd& force) const {
  force.setZero(3 * reference.cols());
  for (const NodalLoad& load : loads_) {
    force[load.dof] += load.scale * (*functions_[load.function])(t, reference.col(load.dof / 3));
  }
}

}  // namespace cc
