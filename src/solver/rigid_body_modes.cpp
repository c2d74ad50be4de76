// Rigid-body motions of each body applied to the free stiffness, and the message naming the
// ones it does not restrain.
#include "solver/rigid_body_modes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace cc {

namespace {

constexpr std::array<RigidMotion, 6> kAllMotions = {
    RigidMotion::TranslationX, RigidMotion::TranslationY, RigidMotion::TranslationZ,
    RigidMotion::RotationX,    RigidMotion::RotationY,    RigidMotion::RotationZ};

// Nodal displacement of `motion` at `position` (rotations about `centroid`), a unit rate.
Eigen::Vector3d motionAt(RigidMotion motion, const Eigen::Vector3d& position,
                         const Eigen::Vector3d& centroid) {
  const int axis = static_cast<int>(motion) % 3;
  const Eigen::Vector3d direction = Eigen::Vector3d::Unit(axis);
  if (static_cast<int>(motion) < 3) return direction;
  return direction.cross(position - centroid);
}

// The motion restricted to the free dofs (prescribed dofs hold it back, so they stay zero).
Eigen::VectorXd freeMotion(RigidMotion motion, const BodyNodes& body, const DofMap& dofs,
                           const Eigen::Matrix3Xd& coordinates, const Eigen::Vector3d& centroid) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(dofs.numFree());
  for (int node : body.nodes) {
    const Eigen::Vector3d value = motionAt(motion, coordinates.col(node), centroid);
    for (int component = 0; component < 3; ++component) {
      const int equation = dofs.equation(3 * node + component);
      if (equation >= 0) r[equation] = value[component];
    }
  }
  return r;
}

// The largest diagonal entry of the whole matrix (summed over the processes' shares).
double largestDiagonal(const SparseMatrix& matrix, const SumOverProcesses& sum) {
  Eigen::VectorXd diagonal = matrix.diagonal();
  if (sum) sum(diagonal);
  return diagonal.size() ? diagonal.cwiseAbs().maxCoeff() : 0.0;
}

std::vector<BodyNodes> allNodesAsOneBody(const DofMap& dofs) {
  BodyNodes body{"model", {}};
  for (int node = 0; node < dofs.numNodes(); ++node) body.nodes.push_back(node);
  return {body};
}

}  // namespace

std::string describe(RigidMotion motion) {
  static constexpr std::array<const char*, 3> kAxes = {"x", "y", "z"};
  const int index = static_cast<int>(motion);
  return fmt::format("{} {}", index < 3 ? "translation along" : "rotation about", kAxes[index % 3]);
}

std::vector<RigidMotionRestraint> rigidMotionRestraints(const SparseMatrix& freeStiffness,
                                                        const DofMap& dofs,
                                                        const Eigen::Matrix3Xd& coordinates,
                                                        const std::vector<BodyNodes>& givenBodies,
                                                        const SumOverProcesses& sum) {
  const std::vector<BodyNodes> bodies = givenBodies.empty() ? allNodesAsOneBody(dofs) : givenBodies;
  const double scale = largestDiagonal(freeStiffness, sum);
  std::vector<RigidMotionRestraint> restraints;
  if (!(scale > 0)) return restraints;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].nodes.empty()) continue;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int node : bodies[b].nodes) centroid += coordinates.col(node);
    centroid /= static_cast<double>(bodies[b].nodes.size());
    for (RigidMotion motion : kAllMotions) {
      const Eigen::VectorXd r = freeMotion(motion, bodies[b], dofs, coordinates, centroid);
      const double length = r.norm();
      if (!(length > 0)) continue;  // every dof it moves is prescribed: held by the supports
      Eigen::VectorXd restoring = freeStiffness * r;
      if (sum) sum(restoring);
      const double ratio = restoring.norm() / (length * scale);
      restraints.push_back({static_cast<int>(b), motion, ratio});
    }
  }
  return restraints;
}

SingularStiffnessDiagnosis describeSingularStiffness(const SparseMatrix& freeStiffness,
                                                     const DofMap& dofs,
                                                     const Eigen::Matrix3Xd& coordinates,
                                                     const std::vector<BodyNodes>& givenBodies,
                                                     const SumOverProcesses& sum) {
  const std::vector<BodyNodes> bodies = givenBodies.empty() ? allNodesAsOneBody(dofs) : givenBodies;
  const std::vector<RigidMotionRestraint> restraints =
      rigidMotionRestraints(freeStiffness, dofs, coordinates, bodies, sum);
  std::vector<std::string> perBody;
  int count = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    std::vector<std::string> motions;
    for (const RigidMotionRestraint& restraint : restraints) {
      if (restraint.body == static_cast<int>(b) && restraint.ratio < kUnrestrainedMotionRatio) {
        motions.push_back(describe(restraint.motion));
      }
    }
    if (motions.empty()) continue;
    count += static_cast<int>(motions.size());
    perBody.push_back(fmt::format("{} of body '{}'", fmt::join(motions, ", "), bodies[b].name));
  }
  if (count > 0) {
    return {fmt::format("unconstrained rigid-body motion{}: {}", count > 1 ? "s" : "",
                        fmt::join(perBody, "; ")),
            true};
  }
  const auto least =
      std::min_element(restraints.begin(), restraints.end(),
                       [](const RigidMotionRestraint& a, const RigidMotionRestraint& b) {
                         return a.ratio < b.ratio;
                       });
  if (least == restraints.end()) return {"no rigid-body motion moves a free dof"};
  return {fmt::format(
      "every rigid-body motion is restrained (the least, {} of body '{}', at {:.2g} of the "
      "stiffest dof): look for a mechanism or a vanishing material stiffness",
      describe(least->motion), bodies[least->body].name, least->ratio)};
}

}  // namespace cc
