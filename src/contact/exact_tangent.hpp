// The exact contact tangent (`tangent exact`): the derivative of the discrete point force, with
// the parallel translation, the slip of eq. (47)/(48), the return mapping and the slave area
// element all linearized, obtained by forward-mode automatic differentiation (Eigen's
// AutoDiffScalar) of the very code that computes the residual, so the two cannot disagree.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <type_traits>
#include <unsupported/Eigen/AutoDiff>

#include "contact/contact_point.hpp"

namespace cc::contact {

// Derivatives on the stack (ItemVector, contact_point.hpp): a heap vector allocated in every AD
// operation.
using AutoDiff = Eigen::AutoDiffScalar<ItemVector>;

namespace detail {
template <class T>
const T& unwrapKinematics(const T& kin) {
  return kin;
}
template <class T>
const T& unwrapKinematics(const std::optional<T>& kin) {
  return *kin;
}
template <class T>
bool hasKinematics(const T&) {
  return true;
}
template <class T>
bool hasKinematics(const std::optional<T>& kin) {
  return kin.has_value();
}
}  // namespace detail

// `kinematics` is a generic callable: NodeMatrix<Scalar> -> PointKinematics<Scalar> (or an
// optional of it), called here with Scalar = AutoDiff. K is sized here (3n x 3n).
template <class KinematicsFn>
void exactTangent(const NodeMatrix<double>& nodes, const PointLayout& layout,
                  const PointHistory& history, const LawParameters& law, KinematicsFn&& kinematics,
                  Eigen::MatrixXd& K) {
  const int dofs = 3 * layout.nodeCount;
  K.setZero(dofs, dofs);
  NodeMatrix<AutoDiff> active(3, layout.nodeCount);
  for (int node = 0; node < layout.nodeCount; ++node) {
    for (int c = 0; c < 3; ++c) {
      active(c, node) = AutoDiff(nodes(c, node), dofs, 3 * node + c);
    }
  }
  const auto kinematicsResult = kinematics(active);
  if (!detail::hasKinematics(kinematicsResult)) return;
  const PointKinematics<AutoDiff>& kin = detail::unwrapKinematics(kinematicsResult);
  const PointResponse<AutoDiff> response = pointResponse(kin, history, law);
  Eigen::Matrix<AutoDiff, Eigen::Dynamic, 1> force;
  pointForce(kin, response, layout, force);
  for (int row = 0; row < dofs; ++row) {
    if (force[row].derivatives().size() == dofs) K.row(row) = force[row].derivatives().transpose();
  }
}

}  // namespace cc::contact
