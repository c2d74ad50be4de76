// Voigt helpers shared by the materials and the elements: the index pairs of the Voigt order
// (11, 22, 33, 12, 23, 13) and conversions between symmetric 3x3 tensors and 6-vectors.
#pragma once

#include <Eigen/Core>
#include <array>

#include "materials/material.hpp"

namespace cc {

// Tensor indices (i, j) of Voigt component I.
inline constexpr std::array<std::array<int, 2>, 6> kVoigtPairs = {
    {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}}};

// Symmetric stress tensor -> Voigt vector (no factor 2). Inverse of stressFromVoigt.
inline Vector6d voigtFromStress(const Eigen::Matrix3d& s) {
  Vector6d v;
  for (int I = 0; I < 6; ++I) v[I] = s(kVoigtPairs[I][0], kVoigtPairs[I][1]);
  return v;
}

// Strain Voigt vector with engineering shears -> symmetric tensor (shears halved).
inline Eigen::Matrix3d strainFromVoigt(const Vector6d& e) {
  Eigen::Matrix3d t;
  t << e[0], 0.5 * e[3], 0.5 * e[5],  //
      0.5 * e[3], e[1], 0.5 * e[4],   //
      0.5 * e[5], 0.5 * e[4], e[2];
  return t;
}

}  // namespace cc
