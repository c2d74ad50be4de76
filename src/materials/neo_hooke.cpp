// Compressible neo-Hooke material, W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2, written in the
// reference configuration: S = mu (I - C^-1) + lambda ln J C^-1 and its consistent tangent.
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <memory>

#include "materials/isotropic.hpp"
#include "materials/material.hpp"
#include "materials/voigt.hpp"

namespace cc {
namespace {

class NeoHooke final : public Material {
 public:
  NeoHooke(double youngsModulus, double poissonRatio)
      : youngsModulus_(youngsModulus),
        poissonRatio_(poissonRatio),
        lame_(lameParameters(youngsModulus, poissonRatio)) {}

  std::string name() const override { return "neo_hooke"; }

  // C = I + 2E must be positive definite; det C <= 0 (no admissible J) is reported as failure.
  bool evaluate(const Vector6d& strainVoigt, Vector6d& stressVoigt,
                Matrix6d* tangent) const override {
    Eigen::Matrix3d Cinv;
    double logJ = 0;
    if (!inverseAndLogJ(strainVoigt, Cinv, logJ)) return false;
    const double lambda = lame_.lambda;
    const double mu = lame_.mu;
    stressVoigt = stress(Cinv, logJ);
    if (tangent != nullptr) {
      // D = 2 dS/dC = lambda C^-1 (x) C^-1 + 2 (mu - lambda ln J) I_{C^-1}, with
      // (I_{C^-1})_ijkl = (C^-1_ik C^-1_jl + C^-1_il C^-1_jk) / 2 from d(C^-1)/dC.
      const Vector6d CinvVoigt = voigtFromStress(Cinv);
      const double shearFactor = mu - lambda * logJ;
      for (int I = 0; I < 6; ++I) {
        const auto [i, j] = kVoigtPairs[I];
        for (int J = I; J < 6; ++J) {
          const auto [k, l] = kVoigtPairs[J];
          const double value = lambda * CinvVoigt[I] * CinvVoigt[J] +
                               shearFactor * (Cinv(i, k) * Cinv(j, l) + Cinv(i, l) * Cinv(j, k));
          (*tangent)(I, J) = value;
          (*tangent)(J, I) = value;
        }
      }
    }
    return true;
  }

  // The tangent above in the IsotropicTangentForm: alpha = lambda, beta = mu - lambda ln J,
  // A = C^-1.
  bool hasIsotropicTangentForm() const override { return true; }
  bool evaluateWithTangentForm(const Vector6d& strainVoigt, Vector6d& stressVoigt,
                               IsotropicTangentForm& tangent) const override {
    Eigen::Matrix3d Cinv;
    double logJ = 0;
    if (!inverseAndLogJ(strainVoigt, Cinv, logJ)) return false;
    stressVoigt = stress(Cinv, logJ);
    tangent = {lame_.lambda, lame_.mu - lame_.lambda * logJ, Cinv};
    return true;
  }

  // W = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2 (the law this file implements).
  double strainEnergy(const Vector6d& strainVoigt) const override {
    const Eigen::Matrix3d C = Eigen::Matrix3d::Identity() + 2.0 * strainFromVoigt(strainVoigt);
    const double detC = C.determinant();
    if (!(detC > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    const double logJ = 0.5 * std::log(detC);
    return 0.5 * lame_.mu * (C.trace() - 3.0) - lame_.mu * logJ + 0.5 * lame_.lambda * logJ * logJ;
  }

  double youngsModulus() const override { return youngsModulus_; }
  double poissonRatio() const override { return poissonRatio_; }

 private:
  // C^-1 and ln J = ln det C / 2 of C = I + 2E; false if det C <= 0.
  static bool inverseAndLogJ(const Vector6d& strainVoigt, Eigen::Matrix3d& Cinv, double& logJ) {
    const Eigen::Matrix3d C = Eigen::Matrix3d::Identity() + 2.0 * strainFromVoigt(strainVoigt);
    const double detC = C.determinant();
    if (!(detC > 0.0)) return false;
    Cinv = C.inverse();
    logJ = 0.5 * std::log(detC);
    return true;
  }
  Vector6d stress(const Eigen::Matrix3d& Cinv, double logJ) const {
    return voigtFromStress(lame_.mu * (Eigen::Matrix3d::Identity() - Cinv) +
                           lame_.lambda * logJ * Cinv);
  }

  double youngsModulus_;
  double poissonRatio_;
  LameParameters lame_;
};

}  // namespace

std::unique_ptr<Material> makeNeoHooke(double youngsModulus, double poissonRatio) {
  return std::make_unique<NeoHooke>(youngsModulus, poissonRatio);
}

}  // namespace cc
