// SolidShell8: tangent against central differences (EAS condensation included) at large strain
// and rotation, objectivity, warm-start independence, failure reporting, and the thin-element
// bending stiffness against plate theory beside the locking Hex8.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <iostream>
#include <vector>

#include "elements/solid_shell.hpp"
#include "fem/shape_functions.hpp"
#include "test_solid_shell_support.hpp"

namespace {

using namespace sstest;

constexpr double kYoung = 2.1e4;
constexpr double kPoisson = 0.3;
// Relative round-off of sums over 8 Gauss points of products of 3x3, 6x6 and 24x24 matrices,
// including the condensation with the (well-conditioned) K_aa: a few thousand ulps.
constexpr double kRoundOff = 1e4 * kEps;
// The FD step is eps^(1/3); the expected error is near eps^(2/3) ~ 4e-11 (support header).
constexpr double kFdRelativeTolerance = 1e-6;

struct Shell8Case {
  NamedMaterial material;
  int easParameters;
};
void PrintTo(const Shell8Case& c, std::ostream* out) {
  *out << c.material.name << "_eas" << c.easParameters;
}

class SolidShell8Test : public ::testing::TestWithParam<Shell8Case> {
 protected:
  std::unique_ptr<cc::Material> material = GetParam().material.make(kYoung, kPoisson);
  std::unique_ptr<cc::ElementKernel> element = cc::makeSolidShell8(GetParam().easParameters);
};
INSTANTIATE_TEST_SUITE_P(SolidShell8, SolidShell8Test,
                         ::testing::Values(Shell8Case{kSvk, 1}, Shell8Case{kNeoHooke, 1},
                                           Shell8Case{kSvk, 5}, Shell8Case{kNeoHooke, 5},
                                           Shell8Case{kSvk, 0}),
                         [](const auto& info) {
                           return std::string(info.param.material.name) + "_eas" +
                                  std::to_string(info.param.easParameters);
                         });

// A shell-like element, 1 x 1 in-plane and 0.25 thick, with every node moved.
Eigen::Matrix3Xd distortedShellElement() {
  Eigen::Matrix<double, 3, 8> offsets;
  offsets << 0.05, -0.08, 0.10, -0.03, 0.07, 0.02, -0.06, 0.04,  //
      -0.04, 0.06, 0.03, -0.09, 0.02, -0.05, 0.08, 0.01,         //
      0.02, -0.01, -0.02, 0.01, -0.015, 0.02, 0.01, -0.02;
  Eigen::Matrix3Xd X = 0.5 * (cc::shape::Hex8::nodeCoordinates().array() + 1.0).matrix();
  X.row(2) *= 0.25;
  return X + offsets;
}

// Stretch 1.4, shear 0.4, thickness compression 0.8 plus a non-homogeneous perturbation that
// bends and twists the element, so that the EAS parameters are active.
Eigen::Matrix3Xd largeStrainConfiguration(const Eigen::Matrix3Xd& X) {
  Matrix3d F;
  F << 1.4, 0.4, 0.0, 0.0, 1.0, 0.1, 0.05, -0.1, 0.8;
  Eigen::Matrix<double, 3, 8> perturbation;
  perturbation << 0.02, -0.03, 0.04, 0.01, -0.02, 0.03, -0.01, 0.02,  //
      0.03, 0.01, -0.02, 0.04, 0.02, -0.03, 0.01, -0.04,              //
      -0.06, 0.08, 0.05, -0.07, 0.04, -0.05, 0.06, 0.03;
  return F * X + perturbation;
}

TEST_P(SolidShell8Test, TangentMatchesCentralDifferencesAtLargeStrain) {
  const Eigen::Matrix3Xd X = distortedShellElement();
  const double error = tangentFdError(*element, X, largeStrainConfiguration(X), *material, 1.0);
  EXPECT_LT(error, kFdRelativeTolerance);
  std::cout << "[ measured ] large strain |K_fd - K|/|K| = " << error << '\n';
}

TEST_P(SolidShell8Test, TangentMatchesCentralDifferencesAfterLargeRotation) {
  const Eigen::Matrix3Xd X = distortedShellElement();
  const Matrix3d R = rotation(120.0, Vector3d(1.0, -2.0, 0.7));
  const Eigen::Matrix3Xd x = (R * largeStrainConfiguration(X)).colwise() + Vector3d(0.3, -1, 2);
  const double error = tangentFdError(*element, X, x, *material, 1.0);
  EXPECT_LT(error, kFdRelativeTolerance);
  std::cout << "[ measured ] strain + 120 deg rotation |K_fd - K|/|K| = " << error << '\n';
}

TEST_P(SolidShell8Test, TangentIsSymmetric) {
  const Eigen::Matrix3Xd X = distortedShellElement();
  Eigen::VectorXd fint;
  Eigen::MatrixXd K;
  ASSERT_TRUE(element->evaluate(X, largeStrainConfiguration(X), *material, {}, fint, &K).ok());
  EXPECT_LT((K - K.transpose()).norm(), kRoundOff * K.norm());
}

// A rigid rotation of the undeformed element leaves no strain: fint = 0 to round-off of the
// stress scale E times the element volume.
TEST_P(SolidShell8Test, RigidRotationGivesZeroForce) {
  const Eigen::Matrix3Xd X = distortedShellElement();
  const Matrix3d R = rotation(75.0, Vector3d(0.3, 1.0, -0.5));
  const Eigen::Matrix3Xd x = (R * X).colwise() + Vector3d(2.0, -1.0, 0.5);
  const Eigen::VectorXd fint = internalForce(*element, X, x, *material);
  EXPECT_LT(fint.cwiseAbs().maxCoeff(), kRoundOff * kYoung * 0.25);
}

// Objectivity: rotating a strained configuration rotates its nodal forces, and the resultant
// force and moment vanish (fint is the variation of a rotation-invariant energy).
TEST_P(SolidShell8Test, ForcesRotateWithTheElementAndAreInEquilibrium) {
  const Eigen::Matrix3Xd X = distortedShellElement();
  const Eigen::Matrix3Xd x = largeStrainConfiguration(X);
  const Matrix3d R = rotation(140.0, Vector3d(-0.4, 0.2, 1.0));
  const Eigen::VectorXd fint = internalForce(*element, X, x, *material);
  const Eigen::VectorXd rotated = internalForce(*element, X, R * x, *material);
  const Eigen::Map<const Eigen::Matrix3Xd> forces(fint.data(), 3, 8);
  const Eigen::Map<const Eigen::Matrix3Xd> rotatedForces(rotated.data(), 3, 8);
  EXPECT_LT((rotatedForces - R * forces).norm(), kRoundOff * fint.norm());
  EXPECT_LT(forces.rowwise().sum().norm(), kRoundOff * fint.norm());
  Vector3d moment = Vector3d::Zero();
  for (int a = 0; a < 8; ++a) moment += x.col(a).cross(forces.col(a));
  EXPECT_LT(moment.norm(), kRoundOff * fint.norm() * x.norm());
}

// The local EAS iteration runs to round-off, so fint does not depend on the warm start, and the
// history receives the converged parameters.
TEST_P(SolidShell8Test, ResultDoesNotDependOnTheWarmStart) {
  const Eigen::Matrix3Xd X = distortedShellElement();
  const Eigen::Matrix3Xd x = largeStrainConfiguration(X);
  const int size = element->historySize();
  ASSERT_EQ(size, GetParam().easParameters);
  std::vector<double> history(size, 0.0);
  Eigen::VectorXd cold, warm, again;
  ASSERT_TRUE(element->evaluate(X, x, *material, history, cold, nullptr).ok());
  const std::vector<double> converged = history;
  std::vector<double> offStart(size, 0.01);  // a different, admissible starting point
  ASSERT_TRUE(element->evaluate(X, x, *material, offStart, warm, nullptr).ok());
  ASSERT_TRUE(element->evaluate(X, x, *material, history, again, nullptr).ok());
  EXPECT_LT((warm - cold).norm(), kRoundOff * cold.norm());
  EXPECT_LT((again - cold).norm(), kRoundOff * cold.norm());
  const double alphaScale = Eigen::Map<const Eigen::VectorXd>(converged.data(), size).norm();
  for (int m = 0; m < size; ++m) EXPECT_NEAR(offStart[m], converged[m], kRoundOff * alphaScale);
}

TEST(SolidShell8, ReportsInvertedAndNonFiniteElements) {
  const auto element = cc::makeSolidShell8(1);
  const auto material = cc::makeNeoHooke(kYoung, kPoisson);
  const Eigen::Matrix3Xd X = distortedShellElement();
  Eigen::Matrix3Xd flipped = X;
  flipped.row(2) *= -1.0;  // mirrored through the mid-plane: det J < 0 everywhere
  Eigen::VectorXd fint;
  cc::ElementStatus status = element->evaluate(X, flipped, *material, {}, fint, nullptr);
  EXPECT_EQ(status.code, cc::ElementStatus::Code::InvertedJacobian) << status.detail;
  EXPECT_NE(status.detail.find("current"), std::string::npos) << status.detail;
  status = element->evaluate(flipped, flipped, *material, {}, fint, nullptr);
  EXPECT_EQ(status.code, cc::ElementStatus::Code::InvertedJacobian) << status.detail;
  Eigen::Matrix3Xd broken = X;
  broken(1, 5) = std::numeric_limits<double>::quiet_NaN();
  status = element->evaluate(X, broken, *material, {}, fint, nullptr);
  EXPECT_EQ(status.code, cc::ElementStatus::Code::NotFinite) << status.detail;
  EXPECT_TRUE(element->cauchyStress(X, broken, *material, {}).array().isNaN().all());
}

TEST(SolidShell8, RejectsUnsupportedEasParameterCounts) {
  for (int count : cc::solidShell8EasParameterCounts()) {
    EXPECT_EQ(cc::makeSolidShell8(count)->historySize(), count);
  }
  EXPECT_THROW(cc::makeSolidShell8(2), std::invalid_argument);
  EXPECT_THROW(cc::makeSolidShell8(-1), std::invalid_argument);
}

}  // namespace
