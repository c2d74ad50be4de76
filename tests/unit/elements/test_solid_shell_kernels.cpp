// SolidShell8 and SolidShell18 kernels: tangent against central differences (EAS condensation
// included) at large strain and rotation for both materials, symmetry, objectivity, warm-start
// independence, and failure reporting (inverted, non-finite, failed local iteration).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "elements/solid_shell.hpp"
#include "fem/shape_functions.hpp"
#include "test_solid_shell_support.hpp"

namespace {

using namespace sstest;

constexpr double kYoung = 2.1e4;
constexpr double kPoisson = 0.3;
// Relative round-off of sums over up to 18 Gauss points of products of 3x3, 6x6 and 54x54
// matrices, including the condensation with the (well-conditioned) K_aa: a few thousand ulps.
constexpr double kRoundOff = 1e4 * kEps;
// The FD step is eps^(1/3); the expected error is near eps^(2/3) ~ 4e-11 (support header).
constexpr double kFdRelativeTolerance = 1e-6;
constexpr double kShellThickness = 0.25;  // of the 1 x 1 test element

// Deterministic "random" offsets in [-amplitude, amplitude] for node a, component i.
double offset(int a, int i, double amplitude) {
  return amplitude * std::sin(1.7 * a + 2.3 * i + 0.4 * a * i);
}

// A shell-like element, 1 x 1 in-plane and 0.25 thick, with every node moved.
template <class Shape>
Eigen::Matrix3Xd distortedShellElement() {
  Eigen::Matrix3Xd X = 0.5 * (Shape::nodeCoordinates().array() + 1.0).matrix();
  X.row(2) *= kShellThickness;
  for (int a = 0; a < X.cols(); ++a) {
    for (int i = 0; i < 3; ++i) X(i, a) += offset(a, i, i == 2 ? 0.02 : 0.06);
  }
  return X;
}

// Stretch 1.4, shear 0.4, thickness compression 0.8 plus a non-homogeneous perturbation that
// bends and twists the element, so that the EAS parameters are active.
Eigen::Matrix3Xd largeStrainConfiguration(const Eigen::Matrix3Xd& X) {
  Matrix3d F;
  F << 1.4, 0.4, 0.0, 0.0, 1.0, 0.1, 0.05, -0.1, 0.8;
  Eigen::Matrix3Xd x = F * X;
  for (int a = 0; a < X.cols(); ++a) {
    for (int i = 0; i < 3; ++i) x(i, a) += offset(a + 5, i + 1, i == 2 ? 0.06 : 0.03);
  }
  return x;
}

struct KernelCase {
  const char* name;
  NamedMaterial material;
  bool quadratic;
  int easParameters;
};
void PrintTo(const KernelCase& c, std::ostream* out) {
  *out << c.name;
}

class SolidShellKernelTest : public ::testing::TestWithParam<KernelCase> {
 protected:
  std::unique_ptr<cc::Material> material = GetParam().material.make(kYoung, kPoisson);
  std::unique_ptr<cc::ElementKernel> element = GetParam().quadratic
                                                   ? cc::makeSolidShell18(GetParam().easParameters)
                                                   : cc::makeSolidShell8(GetParam().easParameters);
  Eigen::Matrix3Xd X = GetParam().quadratic ? distortedShellElement<cc::shape::Hex18>()
                                            : distortedShellElement<cc::shape::Hex8>();
  int nodes() const { return static_cast<int>(X.cols()); }
};
INSTANTIATE_TEST_SUITE_P(SolidShells, SolidShellKernelTest,
                         ::testing::Values(KernelCase{"shell8_svk_eas1", kSvk, false, 1},
                                           KernelCase{"shell8_neo_hooke_eas1", kNeoHooke, false, 1},
                                           KernelCase{"shell8_neo_hooke_eas3", kNeoHooke, false, 3},
                                           KernelCase{"shell8_svk_eas7", kSvk, false, 7},
                                           KernelCase{"shell8_neo_hooke_eas7", kNeoHooke, false, 7},
                                           KernelCase{"shell8_svk_eas0", kSvk, false, 0},
                                           KernelCase{"shell18_svk_eas3", kSvk, true, 3},
                                           KernelCase{"shell18_neo_hooke_eas3", kNeoHooke, true, 3},
                                           KernelCase{"shell18_svk_eas9", kSvk, true, 9},
                                           KernelCase{"shell18_neo_hooke_eas9", kNeoHooke, true,
                                                      9}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST_P(SolidShellKernelTest, TangentMatchesCentralDifferencesAtLargeStrain) {
  const double error = tangentFdError(*element, X, largeStrainConfiguration(X), *material, 1.0);
  EXPECT_LT(error, kFdRelativeTolerance);
  std::cout << "[ measured ] large strain |K_fd - K|/|K| = " << error << '\n';
}

TEST_P(SolidShellKernelTest, TangentMatchesCentralDifferencesAfterLargeRotation) {
  const Matrix3d R = rotation(120.0, Vector3d(1.0, -2.0, 0.7));
  const Eigen::Matrix3Xd x = (R * largeStrainConfiguration(X)).colwise() + Vector3d(0.3, -1, 2);
  const double error = tangentFdError(*element, X, x, *material, 1.0);
  EXPECT_LT(error, kFdRelativeTolerance);
  std::cout << "[ measured ] strain + 120 deg rotation |K_fd - K|/|K| = " << error << '\n';
}

// The stored energy at the enhanced strains in equilibrium with x: its gradient, by central
// differences, is the internal force (dPi/dalpha = 0 removes the parameters' change), and it
// is invariant under a rigid motion.
TEST_P(SolidShellKernelTest, InternalForceIsTheGradientOfTheStrainEnergy) {
  const Eigen::Matrix3Xd x = largeStrainConfiguration(X);
  const Eigen::VectorXd fint = internalForce(*element, X, x, *material);
  const double energy = element->strainEnergy(X, x, *material, {});
  ASSERT_TRUE(std::isfinite(energy));
  ASSERT_GT(energy, 0.0);
  const double h = std::cbrt(kEps);  // the element is 1 x 1 x 0.25: L = 1
  Eigen::VectorXd gradient(fint.size());
  for (int a = 0; a < nodes(); ++a) {
    for (int i = 0; i < 3; ++i) {
      Eigen::Matrix3Xd plus = x, minus = x;
      plus(i, a) += h;
      minus(i, a) -= h;
      gradient[3 * a + i] = (element->strainEnergy(X, plus, *material, {}) -
                             element->strainEnergy(X, minus, *material, {})) /
                            (2 * h);
    }
  }
  const double error = (gradient - fint).norm() / fint.norm();
  EXPECT_LT(error, kFdRelativeTolerance);
  std::cout << "[ measured ] |dW/dx - fint| / |fint| = " << error << '\n';
  const Eigen::Matrix3Xd moved =
      (rotation(120.0, Vector3d(1.0, -2.0, 0.7)) * x).colwise() + Vector3d(0.3, -1, 2);
  EXPECT_NEAR(element->strainEnergy(X, moved, *material, {}), energy, kRoundOff * energy);
}

TEST_P(SolidShellKernelTest, TangentIsSymmetric) {
  Eigen::VectorXd fint;
  Eigen::MatrixXd K;
  ASSERT_TRUE(element->evaluate(X, largeStrainConfiguration(X), *material, {}, fint, &K).ok());
  EXPECT_LT((K - K.transpose()).norm(), kRoundOff * K.norm());
}

// A rigid rotation of the undeformed element leaves no strain: fint = 0 to round-off of the
// stress scale E times the element volume.
TEST_P(SolidShellKernelTest, RigidRotationGivesZeroForce) {
  const Matrix3d R = rotation(75.0, Vector3d(0.3, 1.0, -0.5));
  const Eigen::Matrix3Xd x = (R * X).colwise() + Vector3d(2.0, -1.0, 0.5);
  const Eigen::VectorXd fint = internalForce(*element, X, x, *material);
  EXPECT_LT(fint.cwiseAbs().maxCoeff(), kRoundOff * kYoung * kShellThickness);
}

// Objectivity: rotating a strained configuration rotates its nodal forces, and the resultant
// force and moment vanish (fint is the variation of a rotation-invariant energy).
TEST_P(SolidShellKernelTest, ForcesRotateWithTheElementAndAreInEquilibrium) {
  const Eigen::Matrix3Xd x = largeStrainConfiguration(X);
  const Matrix3d R = rotation(140.0, Vector3d(-0.4, 0.2, 1.0));
  const Eigen::VectorXd fint = internalForce(*element, X, x, *material);
  const Eigen::VectorXd rotated = internalForce(*element, X, R * x, *material);
  const Eigen::Map<const Eigen::Matrix3Xd> forces(fint.data(), 3, nodes());
  const Eigen::Map<const Eigen::Matrix3Xd> rotatedForces(rotated.data(), 3, nodes());
  EXPECT_LT((rotatedForces - R * forces).norm(), kRoundOff * fint.norm());
  EXPECT_LT(forces.rowwise().sum().norm(), kRoundOff * fint.norm());
  Vector3d moment = Vector3d::Zero();
  for (int a = 0; a < nodes(); ++a) moment += x.col(a).cross(forces.col(a));
  EXPECT_LT(moment.norm(), kRoundOff * fint.norm() * x.norm());
}

// The local EAS iteration runs to round-off, so fint does not depend on the warm start, and the
// history receives the converged parameters.
TEST_P(SolidShellKernelTest, ResultDoesNotDependOnTheWarmStart) {
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
  // The enhancement is really active: alpha is a covariant strain, (t/2)^2 times a Cartesian one.
  const double enhancedStrain = alphaScale / std::pow(0.5 * kShellThickness, 2);
  if (size > 0) {
    EXPECT_GT(enhancedStrain, 1e-4);
  }
  for (int m = 0; m < size; ++m) EXPECT_NEAR(offStart[m], converged[m], kRoundOff * alphaScale);
}

TEST_P(SolidShellKernelTest, ReportsInvertedAndNonFiniteElements) {
  Eigen::Matrix3Xd flipped = X;
  flipped.row(2) *= -1.0;  // mirrored through the mid-plane: det J < 0 everywhere
  Eigen::VectorXd fint;
  cc::ElementStatus status = element->evaluate(X, flipped, *material, {}, fint, nullptr);
  EXPECT_EQ(status.code, cc::ElementStatus::Code::InvertedJacobian) << status.detail;
  EXPECT_NE(status.detail.find("current"), std::string::npos) << status.detail;
  status = element->evaluate(flipped, flipped, *material, {}, fint, nullptr);
  EXPECT_EQ(status.code, cc::ElementStatus::Code::InvertedJacobian) << status.detail;
  EXPECT_NE(status.detail.find("reference"), std::string::npos) << status.detail;
  Eigen::Matrix3Xd broken = X;
  broken(1, 5) = std::numeric_limits<double>::quiet_NaN();
  status = element->evaluate(X, broken, *material, {}, fint, nullptr);
  EXPECT_EQ(status.code, cc::ElementStatus::Code::NotFinite) << status.detail;
  EXPECT_TRUE(element->cauchyStress(X, broken, *material, {}).array().isNaN().all());
}

// A law whose tangent is zero (as a softening material at its peak would have) leaves the local
// EAS equations singular: the element must say so instead of returning garbage.
class ZeroTangentMaterial final : public cc::Material {
 public:
  std::string name() const override { return "zero tangent"; }
  bool evaluate(const cc::Vector6d& strain, cc::Vector6d& stress,
                cc::Matrix6d* tangent) const override {
    stress = kYoung * strain;
    if (tangent != nullptr) tangent->setZero();
    return true;
  }
  double youngsModulus() const override { return kYoung; }
  double poissonRatio() const override { return 0.0; }
};

TEST_P(SolidShellKernelTest, ReportsAFailedLocalIteration) {
  if (GetParam().easParameters == 0) GTEST_SKIP() << "no local iteration without EAS";
  Eigen::VectorXd fint;
  const cc::ElementStatus status =
      element->evaluate(X, largeStrainConfiguration(X), ZeroTangentMaterial(), {}, fint, nullptr);
  EXPECT_EQ(status.code, cc::ElementStatus::Code::LocalIterationFailed) << status.detail;
  EXPECT_NE(status.detail.find("EAS"), std::string::npos) << status.detail;
}

TEST(SolidShellFactories, RejectUnsupportedEasParameterCounts) {
  for (int count : cc::solidShell8EasParameterCounts()) {
    EXPECT_EQ(cc::makeSolidShell8(count)->historySize(), count);
  }
  for (int count : cc::solidShell18EasParameterCounts()) {
    EXPECT_EQ(cc::makeSolidShell18(count)->historySize(), count);
  }
  EXPECT_THROW(cc::makeSolidShell8(2), std::invalid_argument);
  EXPECT_THROW(cc::makeSolidShell8(-1), std::invalid_argument);
  EXPECT_THROW(cc::makeSolidShell18(5), std::invalid_argument);
  EXPECT_EQ(cc::makeSolidShell8(1)->numNodes(), 8);
  EXPECT_EQ(cc::makeSolidShell18(1)->numNodes(), 18);
}

}  // namespace
