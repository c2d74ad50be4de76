// Lame constants from (E, nu) and the isotropic Hooke matrix.
#include "materials/isotropic.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace cc {

LameParameters lameParameters(double youngsModulus, double poissonRatio) {
  if (!(std::isfinite(youngsModulus) && youngsModulus > 0.0)) {
    throw std::invalid_argument("Young's modulus must be positive and finite, got " +
                                std::to_string(youngsModulus));
  }
  if (!(poissonRatio > -1.0 && poissonRatio < 0.5)) {
    throw std::invalid_argument("Poisson's ratio must lie in (-1, 0.5), got " +
                                std::to_string(poissonRatio));
  }
  const double mu = youngsModulus / (2.0 * (1.0 + poissonRatio));
  const double lambda =
      youngsModulus * poissonRatio / ((1.0 + poissonRatio) * (1.0 - 2.0 * poissonRatio));
  return {lambda, mu};
}

Matrix6d hookeMatrix(const LameParameters& lame) {
  Matrix6d d = Matrix6d::Zero();
  d.topLeftCorner<3, 3>().setConstant(lame.lambda);
  d.topLeftCorner<3, 3>().diagonal().array() += 2.0 * lame.mu;
  // Engineering shear strains: S_12 = 2 mu E_12 = mu * (2 E_12).
  d.bottomRightCorner<3, 3>().diagonal().setConstant(lame.mu);
  return d;
}

}  // namespace cc
