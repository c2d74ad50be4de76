// Materials: tangent against central differences of the stress, stress against differences of
// an independently written strain energy, the small-strain (Hooke) limit, closed-form uniaxial
// and equibiaxial solutions at large stretch, frame invariance and the failure domain.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <ostream>
#include <stdexcept>

#include "materials/material.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kYoung = 2.1e4;
constexpr double kPoisson = 0.3;
const double kLambda = kYoung * kPoisson / ((1 + kPoisson) * (1 - 2 * kPoisson));
const double kMu = kYoung / (2 * (1 + kPoisson));
// Central differences balance truncation h^2 |S'''| / 6 against round-off eps |S| / h, so the
// step is h = eps^(1/3) times the strain scale (at least 1); the expected relative error is then
// about eps^(2/3) ~ 4e-11, far below the acceptance level kFdRelativeTolerance.
const double kFdStepFactor = std::cbrt(kEps);
constexpr double kFdRelativeTolerance = 1e-6;
// Round-off level of a handful of 3x3 products and one inverse, relative to the stress scale.
constexpr double kRoundOff = 1e3 * kEps;

struct NamedMaterial {
  const char* name;
  std::function<std::unique_ptr<cc::Material>()> make;
};
// Readable parameter names in gtest failure messages.
void PrintTo(const NamedMaterial& material, std::ostream* out) {
  *out << material.name;
}

class MaterialLaw : public ::testing::TestWithParam<NamedMaterial> {
 protected:
  std::unique_ptr<cc::Material> material = GetParam().make();
};

INSTANTIATE_TEST_SUITE_P(
    Materials, MaterialLaw,
    ::testing::Values(
        NamedMaterial{"svk", [] { return cc::makeStVenantKirchhoff(kYoung, kPoisson); }},
        NamedMaterial{"neo_hooke", [] { return cc::makeNeoHooke(kYoung, kPoisson); }},
        NamedMaterial{"neo_hooke_decoupled",
                      [] { return cc::makeNeoHookeDecoupledFromYoung(kYoung, kPoisson); }}),
    [](const auto& info) { return std::string(info.param.name); });

Matrix3d rotation(double angleDegrees, const Vector3d& axis) {
  return Eigen::AngleAxisd(angleDegrees * std::numbers::pi / 180.0, axis.normalized())
      .toRotationMatrix();
}

// Large-strain states: stretch 1.5 with shear 0.5, a compressed and sheared one, a mild one.
std::vector<Matrix3d> deformationGradients() {
  Matrix3d stretchShear;
  stretchShear << 1.5, 0.5, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0;
  Matrix3d compressed;
  compressed << 0.7, 0.2, -0.1, 0.05, 0.9, 0.3, -0.2, 0.1, 1.1;
  Matrix3d mild = Matrix3d::Identity();
  mild(0, 2) = 0.01;
  mild(1, 1) = 1.02;
  return {stretchShear, compressed, mild};
}

cc::Vector6d stressOf(const cc::Material& material, const cc::Vector6d& strain) {
  cc::Vector6d stress;
  EXPECT_TRUE(material.evaluate(strain, stress, nullptr));
  return stress;
}

TEST(Kinematics, GreenLagrangeOfSimpleShearAndStretch) {
  const double gamma = 0.4;
  Matrix3d F = Matrix3d::Identity();
  F(0, 1) = gamma;  // x = X + gamma Y
  F(2, 2) = 1.5;
  cc::Vector6d expected;
  expected << 0.0, 0.5 * gamma * gamma, 0.5 * (1.5 * 1.5 - 1.0), gamma, 0.0, 0.0;
  EXPECT_LT((cc::greenLagrangeVoigt(F) - expected).norm(), kEps);
}

TEST(Kinematics, StressFromVoigtPlacesShearsSymmetrically) {
  cc::Vector6d s;
  s << 1, 2, 3, 4, 5, 6;
  Matrix3d expected;
  expected << 1, 4, 6, 4, 2, 5, 6, 5, 3;
  EXPECT_EQ(cc::stressFromVoigt(s), expected);
}

TEST_P(MaterialLaw, TangentMatchesCentralDifferencesOfStress) {
  for (const Matrix3d& F : deformationGradients()) {
    const cc::Vector6d strain = cc::greenLagrangeVoigt(F);
    cc::Vector6d stress;
    cc::Matrix6d tangent;
    ASSERT_TRUE(material->evaluate(strain, stress, &tangent));
    const double step = kFdStepFactor * std::max(1.0, strain.cwiseAbs().maxCoeff());
    cc::Matrix6d fd;
    for (int j = 0; j < 6; ++j) {
      cc::Vector6d plus = strain, minus = strain;
      plus[j] += step;
      minus[j] -= step;
      fd.col(j) = (stressOf(*material, plus) - stressOf(*material, minus)) / (2 * step);
    }
    const double relativeError = (fd - tangent).norm() / tangent.norm();
    EXPECT_LT(relativeError, kFdRelativeTolerance) << "F =\n" << F;
    EXPECT_LT((tangent - tangent.transpose()).norm(), kRoundOff * tangent.norm());
    std::cout << "[ measured ] " << GetParam().name << " |D_fd - D| / |D| = " << relativeError
              << '\n';
  }
}

// Strain energies written independently of the library (invariants of C), so that S = dW/dE_v
// (engineering shears make S_v . dE_v = S : dE) checks the stress formula itself.
double strainEnergy(const std::string& name, const cc::Vector6d& e) {
  Matrix3d E;
  E << e[0], 0.5 * e[3], 0.5 * e[5], 0.5 * e[3], e[1], 0.5 * e[4], 0.5 * e[5], 0.5 * e[4], e[2];
  if (name == "svk")
    return 0.5 * kLambda * E.trace() * E.trace() + kMu * (E.array().square().sum());
  const Matrix3d C = Matrix3d::Identity() + 2 * E;
  if (name == "neo_hooke_decoupled") {
    // W = C10 (J^(-2/3) I1 - 3) + (J - 1)^2 / D1 with C10 = mu/2, D1 = 2/K.
    const double J = std::sqrt(C.determinant());
    const double bulk = kLambda + 2 * kMu / 3;
    return 0.5 * kMu * (std::pow(J, -2.0 / 3.0) * C.trace() - 3) + 0.5 * bulk * (J - 1) * (J - 1);
  }
  const double logJ = 0.5 * std::log(C.determinant());
  return 0.5 * kMu * (C.trace() - 3) - kMu * logJ + 0.5 * kLambda * logJ * logJ;
}

TEST_P(MaterialLaw, StressIsDerivativeOfStrainEnergy) {
  for (const Matrix3d& F : deformationGradients()) {
    const cc::Vector6d strain = cc::greenLagrangeVoigt(F);
    const cc::Vector6d stress = stressOf(*material, strain);
    const double step = kFdStepFactor * std::max(1.0, strain.cwiseAbs().maxCoeff());
    cc::Vector6d fd;
    for (int j = 0; j < 6; ++j) {
      cc::Vector6d plus = strain, minus = strain;
      plus[j] += step;
      minus[j] -= step;
      fd[j] =
          (strainEnergy(GetParam().name, plus) - strainEnergy(GetParam().name, minus)) / (2 * step);
    }
    EXPECT_LT((fd - stress).norm(), kFdRelativeTolerance * stress.norm()) << "F =\n" << F;
  }
}

TEST_P(MaterialLaw, StoredEnergyIsTheLawsStrainEnergy) {
  for (const Matrix3d& F : deformationGradients()) {
    const cc::Vector6d strain = cc::greenLagrangeVoigt(F);
    const double expected = strainEnergy(GetParam().name, strain);
    EXPECT_NEAR(material->strainEnergy(strain), expected, kRoundOff * kYoung) << "F =\n" << F;
  }
}

// Hooke's matrix from its compliance form (eps = sigma/E - nu/E (tr sigma - sigma), gamma =
// tau/G), independent of the Lame conversion used by the library.
cc::Matrix6d hookeFromCompliance() {
  cc::Matrix6d compliance = cc::Matrix6d::Zero();
  compliance.topLeftCorner<3, 3>().setConstant(-kPoisson / kYoung);
  compliance.topLeftCorner<3, 3>().diagonal().setConstant(1.0 / kYoung);
  compliance.bottomRightCorner<3, 3>().diagonal().setConstant(2 * (1 + kPoisson) / kYoung);
  return compliance.inverse();
}

TEST_P(MaterialLaw, SmallStrainLimitIsHookesLaw) {
  const cc::Matrix6d hooke = hookeFromCompliance();
  cc::Vector6d stress;
  cc::Matrix6d tangent;
  ASSERT_TRUE(material->evaluate(cc::Vector6d::Zero(), stress, &tangent));
  EXPECT_LT(stress.norm(), kRoundOff * kYoung);
  EXPECT_LT((tangent - hooke).norm(), kRoundOff * hooke.norm());

  // A displacement gradient of size delta: S differs from Hooke's linear stress by O(delta^2),
  // i.e. relative O(delta); a factor 10 bounds the constants of the quadratic terms.
  constexpr double kDelta = 1e-6;
  Matrix3d displacementGradient;
  displacementGradient << 0.3, -0.8, 0.5, 0.2, -0.4, 0.9, -0.6, 0.1, 0.7;
  const Matrix3d F = Matrix3d::Identity() + kDelta * displacementGradient;
  const Matrix3d smallStrain = 0.5 * (F + F.transpose()) - Matrix3d::Identity();
  cc::Vector6d smallStrainVoigt;
  smallStrainVoigt << smallStrain(0, 0), smallStrain(1, 1), smallStrain(2, 2),
      2 * smallStrain(0, 1), 2 * smallStrain(1, 2), 2 * smallStrain(0, 2);
  const cc::Vector6d linear = hooke * smallStrainVoigt;
  const cc::Vector6d nonlinear = stressOf(*material, cc::greenLagrangeVoigt(F));
  EXPECT_LT((nonlinear - linear).norm(), 10 * kDelta * linear.norm());
}

TEST_P(MaterialLaw, SecondPiolaStressIsFrameInvariantAndCauchyRotates) {
  const Matrix3d R = rotation(120.0, Vector3d(1, 2, -0.5));
  for (const Matrix3d& F : deformationGradients()) {
    const cc::Vector6d stress = stressOf(*material, cc::greenLagrangeVoigt(F));
    const cc::Vector6d rotatedStress = stressOf(*material, cc::greenLagrangeVoigt(R * F));
    EXPECT_LT((rotatedStress - stress).norm(), kRoundOff * stress.norm());
    const Matrix3d S = cc::stressFromVoigt(stress);
    const Matrix3d cauchy = F * S * F.transpose() / F.determinant();
    const Matrix3d rotatedF = R * F;
    const Matrix3d rotatedCauchy = rotatedF * cc::stressFromVoigt(rotatedStress) *
                                   rotatedF.transpose() / rotatedF.determinant();
    EXPECT_LT((rotatedCauchy - R * cauchy * R.transpose()).norm(), kRoundOff * cauchy.norm());
  }
}

// Root of a monotone scalar function on [low, high] by bisection to machine precision.
double bisect(const std::function<double(double)>& f, double low, double high) {
  constexpr int kBisectionSteps = 200;
  for (int i = 0; i < kBisectionSteps && high - low > kEps * high; ++i) {
    const double mid = 0.5 * (low + high);
    (f(low) * f(mid) <= 0 ? high : low) = mid;
  }
  return 0.5 * (low + high);
}

// Principal second Piola-Kirchhoff stress of neo-Hooke, S_i = (1/l_i) dW/dl_i with
// W = mu/2 (sum l^2 - 3) - mu ln J + lambda/2 ln^2 J, J = l1 l2 l3.
double neoHookePrincipalStress(double stretch, double J) {
  return kMu * (1 - 1 / (stretch * stretch)) + kLambda * std::log(J) / (stretch * stretch);
}

TEST(NeoHooke, UniaxialStressAtLargeStretch) {
  const auto material = cc::makeNeoHooke(kYoung, kPoisson);
  for (const double axialStretch : {2.0, 0.6}) {
    // Lateral stretch making the lateral principal stress vanish.
    const double lateral = bisect(
        [&](double l) { return neoHookePrincipalStress(l, axialStretch * l * l); }, 0.2, 5.0);
    const double J = axialStretch * lateral * lateral;
    const Vector3d stretches(axialStretch, lateral, lateral);
    const cc::Vector6d stress =
        stressOf(*material, cc::greenLagrangeVoigt(stretches.asDiagonal().toDenseMatrix()));
    const double axialStress = neoHookePrincipalStress(axialStretch, J);
    EXPECT_NEAR(stress[0], axialStress, kRoundOff * std::abs(axialStress));
    EXPECT_NEAR(stress[1], 0.0, kRoundOff * std::abs(axialStress));
    EXPECT_NEAR(stress[2], 0.0, kRoundOff * std::abs(axialStress));
    EXPECT_LT(stress.tail<3>().norm(), kRoundOff * std::abs(axialStress));
    // Cauchy stress sigma = (mu (l^2 - 1) + lambda ln J) / J along the axis.
    const double cauchy = axialStretch * axialStretch * stress[0] / J;
    const double closedForm = (kMu * (axialStretch * axialStretch - 1) + kLambda * std::log(J)) / J;
    EXPECT_NEAR(cauchy, closedForm, kRoundOff * std::abs(closedForm));
  }
}

TEST(NeoHooke, EquibiaxialStressAtLargeStretch) {
  const auto material = cc::makeNeoHooke(kYoung, kPoisson);
  const double inPlane = 1.8;
  const double thickness = bisect(
      [&](double l) { return neoHookePrincipalStress(l, inPlane * inPlane * l); }, 0.05, 2.0);
  const double J = inPlane * inPlane * thickness;
  const Vector3d stretches(inPlane, inPlane, thickness);
  const cc::Vector6d stress =
      stressOf(*material, cc::greenLagrangeVoigt(stretches.asDiagonal().toDenseMatrix()));
  const double inPlaneStress = neoHookePrincipalStress(inPlane, J);
  EXPECT_NEAR(stress[0], inPlaneStress, kRoundOff * inPlaneStress);
  EXPECT_NEAR(stress[1], inPlaneStress, kRoundOff * inPlaneStress);
  EXPECT_NEAR(stress[2], 0.0, kRoundOff * inPlaneStress);
}

// Decoupled neo-Hooke, principal Cauchy stress with k = 2/D1 = K:
// sigma_i = 2 C10 J^(-5/3) (l_i^2 - I1/3) + K (J - 1).
const double kBulk = kLambda + 2 * kMu / 3;
double decoupledPrincipalCauchy(const Vector3d& stretches, int i) {
  const double J = stretches.prod();
  const double I1 = stretches.squaredNorm();
  return kMu * std::pow(J, -5.0 / 3.0) * (stretches[i] * stretches[i] - I1 / 3) + kBulk * (J - 1);
}

TEST(NeoHookeDecoupled, UniaxialStressAtLargeStretch) {
  const auto material = cc::makeNeoHookeDecoupledFromYoung(kYoung, kPoisson);
  for (const double axialStretch : {2.0, 0.6}) {
    const double lateral =
        bisect([&](double l) { return decoupledPrincipalCauchy(Vector3d(axialStretch, l, l), 1); },
               0.2, 5.0);
    const Vector3d stretches(axialStretch, lateral, lateral);
    const double J = stretches.prod();
    const cc::Vector6d stress =
        stressOf(*material, cc::greenLagrangeVoigt(stretches.asDiagonal().toDenseMatrix()));
    // S_1 = J sigma_1 / l_1^2.
    const double axialStress =
        J * decoupledPrincipalCauchy(stretches, 0) / (axialStretch * axialStretch);
    EXPECT_NEAR(stress[0], axialStress, kRoundOff * std::abs(axialStress));
    EXPECT_NEAR(stress[1], 0.0, kRoundOff * std::abs(axialStress));
    EXPECT_NEAR(stress[2], 0.0, kRoundOff * std::abs(axialStress));
    EXPECT_LT(stress.tail<3>().norm(), kRoundOff * std::abs(axialStress));
  }
}

// Pure dilatation F = l I: no isochoric stress, sigma = K (J - 1) I, J = l^3.
TEST(NeoHookeDecoupled, HydrostaticStressOfPureDilatation) {
  const auto material = cc::makeNeoHookeDecoupledFromYoung(kYoung, kPoisson);
  for (const double l : {1.3, 0.8}) {
    const double J = l * l * l;
    const cc::Vector6d stress =
        stressOf(*material, cc::greenLagrangeVoigt(l * Matrix3d::Identity()));
    const double expected = J * kBulk * (J - 1) / (l * l);  // S = J sigma / l^2
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(stress[i], expected, kRoundOff * std::abs(expected));
    EXPECT_LT(stress.tail<3>().norm(), kRoundOff * std::abs(expected));
  }
}

// Simple shear x = X + gamma Y (J = 1): sigma_12 = mu gamma at any gamma (the Mooney-Rivlin
// result with C01 = 0), and the normal stress difference sigma_11 - sigma_22 = mu gamma^2.
TEST(NeoHookeDecoupled, SimpleShearIsLinearInShear) {
  const auto material = cc::makeNeoHookeDecoupledFromYoung(kYoung, kPoisson);
  const double gamma = 0.8;
  Matrix3d F = Matrix3d::Identity();
  F(0, 1) = gamma;
  const Matrix3d sigma =
      F * cc::stressFromVoigt(stressOf(*material, cc::greenLagrangeVoigt(F))) * F.transpose();
  EXPECT_NEAR(sigma(0, 1), kMu * gamma, kRoundOff * kMu);
  EXPECT_NEAR(sigma(0, 0) - sigma(1, 1), kMu * gamma * gamma, kRoundOff * kMu);
}

TEST(NeoHookeDecoupled, FromC10D1HasTheSmallStrainConstants) {
  const auto fromYoung = cc::makeNeoHookeDecoupledFromYoung(kYoung, kPoisson);
  const auto fromC10 = cc::makeNeoHookeDecoupled(kMu / 2, 2 / kBulk);
  EXPECT_NEAR(fromC10->youngsModulus(), kYoung, kRoundOff * kYoung);
  EXPECT_NEAR(fromC10->poissonRatio(), kPoisson, kRoundOff);
  cc::Matrix6d a, b;
  cc::Vector6d s;
  const cc::Vector6d strain = cc::greenLagrangeVoigt(deformationGradients()[1]);
  ASSERT_TRUE(fromYoung->evaluate(strain, s, &a));
  ASSERT_TRUE(fromC10->evaluate(strain, s, &b));
  EXPECT_LT((a - b).norm(), kRoundOff * a.norm());
  EXPECT_THROW(cc::makeNeoHookeDecoupled(0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(cc::makeNeoHookeDecoupled(1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(cc::makeNeoHookeDecoupledFromYoung(1.0, 0.5), std::invalid_argument);
}

// St. Venant-Kirchhoff under uniaxial S: E22 = -nu E11 and S11 = Young * E11 at any stretch.
TEST(StVenantKirchhoff, UniaxialStressAtLargeStretch) {
  const auto material = cc::makeStVenantKirchhoff(kYoung, kPoisson);
  const double axialStretch = 1.6;
  const double axialStrain = 0.5 * (axialStretch * axialStretch - 1);
  const double lateral = std::sqrt(1 - 2 * kPoisson * axialStrain);
  const Vector3d stretches(axialStretch, lateral, lateral);
  const cc::Vector6d stress =
      stressOf(*material, cc::greenLagrangeVoigt(stretches.asDiagonal().toDenseMatrix()));
  EXPECT_NEAR(stress[0], kYoung * axialStrain, kRoundOff * kYoung * axialStrain);
  EXPECT_LT(stress.tail<5>().norm(), kRoundOff * kYoung * axialStrain);
}

TEST(NeoHooke, RejectsStrainsWithoutPositiveDeterminant) {
  const auto material = cc::makeNeoHooke(kYoung, kPoisson);
  cc::Vector6d stress;
  cc::Matrix6d tangent;
  cc::Vector6d collapsed = cc::Vector6d::Zero();
  collapsed[0] = -0.5;  // C11 = 0: det C = 0
  EXPECT_FALSE(material->evaluate(collapsed, stress, &tangent));
  cc::Vector6d negative = cc::Vector6d::Zero();
  negative[2] = -0.7;  // C33 < 0: det C < 0
  EXPECT_FALSE(material->evaluate(negative, stress, &tangent));
  cc::Vector6d notANumber = cc::Vector6d::Zero();
  notANumber[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(material->evaluate(notANumber, stress, nullptr));
}

TEST_P(MaterialLaw, ReportsItsElasticConstants) {
  EXPECT_EQ(material->youngsModulus(), kYoung);
  EXPECT_EQ(material->poissonRatio(), kPoisson);
  EXPECT_EQ(material->name(), GetParam().name);
}

TEST(Factories, RejectInadmissibleConstants) {
  EXPECT_THROW(cc::makeStVenantKirchhoff(-1.0, 0.3), std::invalid_argument);
  EXPECT_THROW(cc::makeStVenantKirchhoff(1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(cc::makeNeoHooke(0.0, 0.3), std::invalid_argument);
  EXPECT_THROW(cc::makeNeoHooke(1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(cc::makeNeoHooke(std::numeric_limits<double>::infinity(), 0.3),
               std::invalid_argument);
}

}  // namespace
