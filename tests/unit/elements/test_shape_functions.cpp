// Shape functions of every family: node coordinates against gmsh's reference elements, Kronecker
// property, partition of unity, polynomial reproduction, and first/second derivatives against
// central finite differences.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "fem/shape_functions.hpp"

namespace {

using namespace cc::shape;

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Sums of at most 27 products of 1D polynomials of size <= 1: a few ulps.
constexpr double kRoundOff = 32 * kEps;
// Central differences: truncation h^2 |N'''|/6 against round-off eps |N| / h is balanced by
// h = eps^(1/3). The 1D Lagrange factors (degree <= 2) and their derivatives are bounded by 2 on
// [-1,1], so |N'''| products stay below 8; kFdBoundFactor covers that with a margin.
const double kFdStep = std::cbrt(kEps);
constexpr double kFdBoundFactor = 16.0;
const double kFdTolerance = kFdBoundFactor * (kFdStep * kFdStep + kEps / kFdStep);

// Polynomial degree per direction of each family (for the reproduction test).
template <class Family>
std::array<int, Family::kDim> degrees();
template <>
std::array<int, 2> degrees<Quad4>() {
  return {1, 1};
}
template <>
std::array<int, 2> degrees<Quad9>() {
  return {2, 2};
}
template <>
std::array<int, 3> degrees<Hex8>() {
  return {1, 1, 1};
}
template <>
std::array<int, 3> degrees<Hex27>() {
  return {2, 2, 2};
}
template <>
std::array<int, 3> degrees<Hex18>() {
  return {2, 2, 1};
}

template <class Family>
std::vector<typename Family::Point> samplePoints() {
  constexpr int kSamples = 20;
  std::mt19937 generator(12345);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  std::vector<typename Family::Point> points(kSamples);
  for (auto& p : points) {
    for (int d = 0; d < Family::kDim; ++d) p[d] = coordinate(generator);
  }
  return points;
}

template <class Family>
class ShapeFamily : public ::testing::Test {};
using Families = ::testing::Types<Quad4, Quad9, Hex8, Hex27, Hex18>;
TYPED_TEST_SUITE(ShapeFamily, Families);

TYPED_TEST(ShapeFamily, KroneckerPropertyAtNodes) {
  const auto nodes = TypeParam::nodeCoordinates();
  for (int b = 0; b < TypeParam::kNodes; ++b) {
    const typename TypeParam::Point node = nodes.col(b);
    const auto n = TypeParam::values(node);
    for (int a = 0; a < TypeParam::kNodes; ++a) {
      EXPECT_NEAR(n[a], a == b ? 1.0 : 0.0, kRoundOff) << "N_" << a << " at node " << b;
    }
  }
}

TYPED_TEST(ShapeFamily, PartitionOfUnityAndZeroSumDerivatives) {
  for (const auto& xi : samplePoints<TypeParam>()) {
    EXPECT_NEAR(TypeParam::values(xi).sum(), 1.0, kRoundOff);
    const Eigen::Matrix<double, 1, TypeParam::kDim> gradientSums =
        TypeParam::gradients(xi).colwise().sum();
    for (int i = 0; i < TypeParam::kDim; ++i) EXPECT_NEAR(gradientSums[i], 0.0, kRoundOff);
  }
}

// Nodal interpolation reproduces the highest tensor-product monomial of the family exactly (and
// hence, via the Kronecker property, identifies each node's position with its function).
TYPED_TEST(ShapeFamily, ReproducesHighestTensorMonomial) {
  const auto nodes = TypeParam::nodeCoordinates();
  const auto degree = degrees<TypeParam>();
  auto monomial = [&](const typename TypeParam::Point& p) {
    double value = 1.0;
    for (int d = 0; d < TypeParam::kDim; ++d) value *= std::pow(p[d], degree[d]);
    return value;
  };
  for (const auto& xi : samplePoints<TypeParam>()) {
    const auto n = TypeParam::values(xi);
    double interpolated = 0;
    for (int a = 0; a < TypeParam::kNodes; ++a) {
      interpolated += n[a] * monomial(nodes.col(a));
    }
    EXPECT_NEAR(interpolated, monomial(xi), kRoundOff);
    // Linear fields: sum_a N_a xi_a = xi.
    const typename TypeParam::Point position = nodes * n;
    EXPECT_LT((position - xi).norm(), kRoundOff);
  }
}

TYPED_TEST(ShapeFamily, GradientsMatchCentralDifferences) {
  for (const auto& xi : samplePoints<TypeParam>()) {
    const auto analytic = TypeParam::gradients(xi);
    for (int i = 0; i < TypeParam::kDim; ++i) {
      typename TypeParam::Point plus = xi, minus = xi;
      plus[i] += kFdStep;
      minus[i] -= kFdStep;
      const typename TypeParam::Values fd =
          (TypeParam::values(plus) - TypeParam::values(minus)) / (2 * kFdStep);
      EXPECT_LT((fd - analytic.col(i)).cwiseAbs().maxCoeff(), kFdTolerance) << "direction " << i;
    }
  }
}

template <class Family>
class SurfaceFamily : public ::testing::Test {};
using SurfaceFamilies = ::testing::Types<Quad4, Quad9>;
TYPED_TEST_SUITE(SurfaceFamily, SurfaceFamilies);

TYPED_TEST(SurfaceFamily, SecondDerivativesMatchCentralDifferencesOfGradients) {
  // Column order of secondDerivatives: (1,1), (1,2), (2,2), as SurfaceShape::second.
  constexpr std::array<std::array<int, 2>, 3> kPairs = {{{0, 0}, {0, 1}, {1, 1}}};
  for (const auto& xi : samplePoints<TypeParam>()) {
    const auto analytic = TypeParam::secondDerivatives(xi);
    EXPECT_LT(analytic.colwise().sum().cwiseAbs().maxCoeff(), kRoundOff);
    for (int c = 0; c < 3; ++c) {
      const auto [i, j] = kPairs[c];
      typename TypeParam::Point plus = xi, minus = xi;
      plus[j] += kFdStep;
      minus[j] -= kFdStep;
      const typename TypeParam::Values fd =
          (TypeParam::gradients(plus).col(i) - TypeParam::gradients(minus).col(i)) / (2 * kFdStep);
      EXPECT_LT((fd - analytic.col(c)).cwiseAbs().maxCoeff(), kFdTolerance) << "pair " << c;
    }
  }
}

TEST(SurfaceFamily, Quad4HasOnlyTheMixedSecondDerivative) {
  const auto second = Quad4::secondDerivatives(Eigen::Vector2d(0.3, -0.7));
  EXPECT_EQ(second.col(0).norm(), 0.0);
  EXPECT_EQ(second.col(2).norm(), 0.0);
  const Eigen::Vector4d expectedMixed(0.25, -0.25, 0.25, -0.25);  // N_a = (1 +- xi)(1 +- eta)/4
  EXPECT_LT((second.col(1) - expectedMixed).norm(), kRoundOff);
}

// gmsh is the authority on its node orders: compare with its reference element definitions.
class GmshReference : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    gmsh::initialize();
    gmsh::option::setNumber("General.Terminal", 0);
  }
  static void TearDownTestSuite() { gmsh::finalize(); }

  static Eigen::MatrixXd gmshNodes(int elementType, int expectedNodes) {
    std::string name;
    int dim = 0, order = 0, numNodes = 0, numPrimary = 0;
    std::vector<double> coordinates;
    gmsh::model::mesh::getElementProperties(elementType, name, dim, order, numNodes, coordinates,
                                            numPrimary);
    EXPECT_EQ(numNodes, expectedNodes) << name;
    return Eigen::Map<Eigen::MatrixXd>(coordinates.data(), dim, numNodes);
  }
};

// gmsh element type numbers (gmsh documentation, "MSH file format").
constexpr int kGmshQuad4 = 3;
constexpr int kGmshQuad9 = 10;
constexpr int kGmshHex8 = 5;
constexpr int kGmshHex27 = 12;

TEST_F(GmshReference, NodeCoordinatesMatchGmsh) {
  EXPECT_EQ(gmshNodes(kGmshQuad4, 4), Eigen::MatrixXd(Quad4::nodeCoordinates()));
  EXPECT_EQ(gmshNodes(kGmshQuad9, 9), Eigen::MatrixXd(Quad9::nodeCoordinates()));
  EXPECT_EQ(gmshNodes(kGmshHex8, 8), Eigen::MatrixXd(Hex8::nodeCoordinates()));
  EXPECT_EQ(gmshNodes(kGmshHex27, 27), Eigen::MatrixXd(Hex27::nodeCoordinates()));
}

TEST(Hex18, IsQuad9TimesLinearInZeta) {
  const auto hex18 = Hex18::nodeCoordinates();
  const auto quad9 = Quad9::nodeCoordinates();
  for (int a = 0; a < 9; ++a) {
    EXPECT_EQ(hex18.col(a).head<2>(), quad9.col(a));
    EXPECT_EQ(hex18(2, a), -1.0);
    EXPECT_EQ(hex18.col(9 + a).head<2>(), quad9.col(a));
    EXPECT_EQ(hex18(2, 9 + a), 1.0);
  }
  const Eigen::Vector3d xi(0.2, -0.4, 0.7);
  const auto n18 = Hex18::values(xi);
  const auto n9 = Quad9::values(xi.head<2>());
  for (int a = 0; a < 9; ++a) {
    EXPECT_NEAR(n18[a], n9[a] * 0.5 * (1 - xi[2]), kRoundOff);
    EXPECT_NEAR(n18[9 + a], n9[a] * 0.5 * (1 + xi[2]), kRoundOff);
  }
}

}  // namespace
