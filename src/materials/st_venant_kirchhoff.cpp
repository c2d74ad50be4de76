// St. Venant-Kirchhoff material: Hooke's law between the Green-Lagrange strain and the second
// Piola-Kirchhoff stress, S = lambda tr(E) I + 2 mu E, with a constant tangent.
#include <memory>

#include "materials/isotropic.hpp"
#include "materials/material.hpp"

namespace cc {
namespace {

class StVenantKirchhoff final : public Material {
 public:
  StVenantKirchhoff(double youngsModulus, double poissonRatio)
      : youngsModulus_(youngsModulus),
        poissonRatio_(poissonRatio),
        lame_(lameParameters(youngsModulus, poissonRatio)),
        hooke_(hookeMatrix(lame_)) {}

  std::string name() const override { return "svk"; }

  // Defined for every strain (it is linear), so it never reports failure.
  bool evaluate(const Vector6d& strainVoigt, Vector6d& stressVoigt,
                Matrix6d* tangent) const override {
    stressVoigt.noalias() = hooke_ * strainVoigt;
    if (tangent != nullptr) *tangent = hooke_;
    return true;
  }

  // D = lambda I (x) I + 2 mu I (.) I.
  bool hasIsotropicTangentForm() const override { return true; }
  bool evaluateWithTangentForm(const Vector6d& strainVoigt, Vector6d& stressVoigt,
                               IsotropicTangentForm& tangent) const override {
    stressVoigt.noalias() = hooke_ * strainVoigt;
    tangent = {lame_.lambda, lame_.mu, Eigen::Matrix3d::Identity()};
    return true;
  }

  // W = 1/2 E : C : E (engineering shears: S_v . E_v = S : E).
  double strainEnergy(const Vector6d& strainVoigt) const override {
    return 0.5 * strainVoigt.dot(hooke_ * strainVoigt);
  }

  double youngsModulus() const override { return youngsModulus_; }
  double poissonRatio() const override { return poissonRatio_; }

 private:
  double youngsModulus_;
  double poissonRatio_;
  LameParameters lame_;
  Matrix6d hooke_;
};

}  // namespace

std::unique_ptr<Material> makeStVenantKirchhoff(double youngsModulus, double poissonRatio) {
  return std::make_unique<StVenantKirchhoff>(youngsModulus, poissonRatio);
}

}  // namespace cc
