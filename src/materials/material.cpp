// Kinematic conversions shared by all materials: Green-Lagrange strain from the deformation
// gradient and Voigt stress vectors to tensors.
#include "materials/material.hpp"

#include <Eigen/Core>

namespace cc {

Vector6d greenLagrangeVoigt(const Eigen::Matrix3d& F) {
  // E = (F^T F - I) / 2; shears are stored as engineering strains 2 E_ij = C_ij.
  const Eigen::Matrix3d C = F.transpose() * F;
  Vector6d e;
  e << 0.5 * (C(0, 0) - 1.0), 0.5 * (C(1, 1) - 1.0), 0.5 * (C(2, 2) - 1.0), C(0, 1), C(1, 2),
      C(0, 2);
  return e;
}

Eigen::Matrix3d stressFromVoigt(const Vector6d& s) {
  Eigen::Matrix3d t;
  t << s[0], s[3], s[5],  //
      s[3], s[1], s[4],   //
      s[5], s[4], s[2];
  return t;
}

}  // namespace cc
