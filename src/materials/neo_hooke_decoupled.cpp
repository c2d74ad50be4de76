// Decoupled (isochoric/volumetric) neo-Hooke material, the Abaqus/CalculiX form
//   W = C10 (I1bar - 3) + (J - 1)^2 / D1,   I1bar = J^(-2/3) I1,
// with C10 = mu/2 and D1 = 2/K for the small-strain shear and bulk moduli (issue 14: decks
// ported from those codes expect it; it differs from neo_hooke.cpp at finite volume change).
// In the reference configuration, with k = 2/D1:
//   S = 2 C10 J^(-2/3) (I - I1/3 C^-1) + k J (J - 1) C^-1,
//   D = 2 dS/dC (derivation in the comments of evaluate()).
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "materials/isotropic.hpp"
#include "materials/material.hpp"
#include "materials/voigt.hpp"

namespace cc {
namespace {

class NeoHookeDecoupled final : public Material {
 public:
  // E and nu: the small-strain constants as given (when built from them), else from C10, D1.
  NeoHookeDecoupled(double c10, double d1, double youngsModulus, double poissonRatio)
      : c10_(c10), d1_(d1), youngsModulus_(youngsModulus), poissonRatio_(poissonRatio) {
    if (!(c10 > 0) || !(d1 > 0) || !std::isfinite(c10) || !std::isfinite(d1)) {
      throw std::invalid_argument("neohooke_decoupled: C10 and D1 must be finite and > 0");
    }
  }

  std::string name() const override { return "neo_hooke_decoupled"; }

  bool evaluate(const Vector6d& strainVoigt, Vector6d& stressVoigt,
                Matrix6d* tangent) const override {
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d C = I + 2.0 * strainFromVoigt(strainVoigt);
    const double detC = C.determinant();
    if (!(detC > 0.0)) return false;
    const Eigen::Matrix3d Cinv = C.inverse();
    const double J = std::sqrt(detC);
    const double I1 = C.trace();
    const double a = 2.0 * c10_ * std::pow(J, -2.0 / 3.0);  // 2 C10 J^(-2/3)
    const double k = 2.0 / d1_;
    stressVoigt = voigtFromStress(a * (I - I1 / 3.0 * Cinv) + k * J * (J - 1.0) * Cinv);
    if (tangent != nullptr) {
      // With dJ/dC = J C^-1 / 2, dI1/dC = I, dC^-1/dC = -I_{C^-1}
      // ((I_{C^-1})_ijkl = (C^-1_ik C^-1_jl + C^-1_il C^-1_jk) / 2):
      //  isochoric: D = 2 a [-(I (x) C^-1 + C^-1 (x) I)/3 + I1/9 C^-1 (x) C^-1 + I1/3 I_{C^-1}]
      //  volumetric: D = k J (2J - 1) C^-1 (x) C^-1 - 2 k J (J - 1) I_{C^-1}
      const Vector6d iv = voigtFromStress(I);
      const Vector6d cv = voigtFromStress(Cinv);
      const double cc = 2.0 * a * I1 / 9.0 + k * J * (2.0 * J - 1.0);
      const double ic = 2.0 * a / 3.0;
      const double sym = a * I1 / 3.0 - k * J * (J - 1.0);  // times (C^-1_ik C^-1_jl + ...)
      for (int P = 0; P < 6; ++P) {
        const auto [i, j] = kVoigtPairs[P];
        for (int Q = P; Q < 6; ++Q) {
          const auto [m, n] = kVoigtPairs[Q];
          const double value = cc * cv[P] * cv[Q] - ic * (iv[P] * cv[Q] + cv[P] * iv[Q]) +
                               sym * (Cinv(i, m) * Cinv(j, n) + Cinv(i, n) * Cinv(j, m));
          (*tangent)(P, Q) = value;
          (*tangent)(Q, P) = value;
        }
      }
    }
    return true;
  }

  // W = C10 (J^(-2/3) I1 - 3) + (J - 1)^2 / D1 (the law this file implements).
  double strainEnergy(const Vector6d& strainVoigt) const override {
    const Eigen::Matrix3d C = Eigen::Matrix3d::Identity() + 2.0 * strainFromVoigt(strainVoigt);
    const double detC = C.determinant();
    if (!(detC > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    const double J = std::sqrt(detC);
    return c10_ * (std::pow(J, -2.0 / 3.0) * C.trace() - 3.0) + (J - 1.0) * (J - 1.0) / d1_;
  }

  double youngsModulus() const override { return youngsModulus_; }
  double poissonRatio() const override { return poissonRatio_; }

 private:
  double c10_;
  double d1_;
  double youngsModulus_;
  double poissonRatio_;
};

}  // namespace

// Small-strain constants: mu = 2 C10, K = 2 / D1.
std::unique_ptr<Material> makeNeoHookeDecoupled(double c10, double d1) {
  const double mu = 2.0 * c10, bulk = 2.0 / d1;
  return std::make_unique<NeoHookeDecoupled>(c10, d1, 9.0 * bulk * mu / (3.0 * bulk + mu),
                                             (3.0 * bulk - 2.0 * mu) / (2.0 * (3.0 * bulk + mu)));
}

std::unique_ptr<Material> makeNeoHookeDecoupledFromYoung(double youngsModulus,
                                                         double poissonRatio) {
  const LameParameters lame = lameParameters(youngsModulus, poissonRatio);  // validates E, nu
  const double bulk = lame.lambda + 2.0 * lame.mu / 3.0;
  return std::make_unique<NeoHookeDecoupled>(lame.mu / 2.0, 2.0 / bulk, youngsModulus,
                                             poissonRatio);
}

}  // namespace cc
