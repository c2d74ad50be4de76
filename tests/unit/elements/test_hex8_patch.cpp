// Hex8 patch test (type A): a distorted 2x2x2 patch under a homogeneous large deformation
// x = F X reproduces the analytic stress at every Gauss point, leaves the interior node in
// equilibrium and integrates the first Piola stress over the patch volume exactly.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <ostream>
#include <vector>

#include "elements/hex8.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kYoung = 2.1e4;
constexpr double kPoisson = 0.3;
const double kLambda = kYoung * kPoisson / ((1 + kPoisson) * (1 - 2 * kPoisson));
const double kMu = kYoung / (2 * (1 + kPoisson));
constexpr double kRoundOff = 1e3 * kEps;  // relative, see test_elements.cpp

constexpr int kNodesPerSide = 3;  // 2 elements per direction
constexpr int kPatchNodes = kNodesPerSide * kNodesPerSide * kNodesPerSide;
constexpr int kInteriorNode = 13;  // grid position (1, 1, 1)
constexpr double kPatchSize = 2.0;

int gridNode(int i, int j, int k) {
  return i + kNodesPerSide * (j + kNodesPerSide * k);
}

struct Patch {
  Eigen::Matrix3Xd nodes{3, kPatchNodes};
  std::vector<std::array<int, 8>> elements;
};

// [0,2]^3 split into 8 hexes; the interior node is moved off-centre and mid-face nodes slide
// within their (planar) faces, so no element is a parallelepiped.
Patch distortedPatch() {
  Patch patch;
  for (int k = 0; k < kNodesPerSide; ++k) {
    for (int j = 0; j < kNodesPerSide; ++j) {
      for (int i = 0; i < kNodesPerSide; ++i)
        patch.nodes.col(gridNode(i, j, k)) = Vector3d(i, j, k);
    }
  }
  patch.nodes.col(kInteriorNode) = Vector3d(1.17, 0.89, 1.11);
  patch.nodes.col(gridNode(1, 1, 0)) += Vector3d(0.12, -0.07, 0.0);  // bottom face centre
  patch.nodes.col(gridNode(2, 1, 1)) += Vector3d(0.0, 0.09, -0.13);  // face X = 2
  patch.nodes.col(gridNode(1, 2, 1)) += Vector3d(-0.1, 0.0, 0.08);   // face Y = 2
  patch.nodes.col(gridNode(1, 0, 2)) += Vector3d(0.06, 0.0, 0.0);    // edge on Z = 2, Y = 0
  constexpr std::array<std::array<int, 3>, 8> kCornerOffsets = {
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  for (int ek = 0; ek < 2; ++ek) {
    for (int ej = 0; ej < 2; ++ej) {
      for (int ei = 0; ei < 2; ++ei) {
        std::array<int, 8> connectivity;
        for (int a = 0; a < 8; ++a) {
          const auto& o = kCornerOffsets[a];
          connectivity[a] = gridNode(ei + o[0], ej + o[1], ek + o[2]);
        }
        patch.elements.push_back(connectivity);
      }
    }
  }
  return patch;
}

cc::Hex8Nodes gather(const Eigen::Matrix3Xd& coordinates, const std::array<int, 8>& nodes) {
  cc::Hex8Nodes local;
  for (int a = 0; a < 8; ++a) local.col(a) = coordinates.col(nodes[a]);
  return local;
}

// The two laws written out directly from their definitions, independently of the library.
Matrix3d analyticSecondPiola(const std::string& law, const Matrix3d& F) {
  const Matrix3d C = F.transpose() * F;
  const Matrix3d I = Matrix3d::Identity();
  if (law == "svk") {
    const Matrix3d E = 0.5 * (C - I);
    return kLambda * E.trace() * I + 2 * kMu * E;
  }
  const Matrix3d Cinv = C.inverse();
  return kMu * (I - Cinv) + kLambda * std::log(F.determinant()) * Cinv;
}

struct NamedMaterial {
  const char* name;
  std::function<std::unique_ptr<cc::Material>()> make;
};
// Readable parameter names in gtest failure messages.
void PrintTo(const NamedMaterial& material, std::ostream* out) {
  *out << material.name;
}

class Hex8PatchTest : public ::testing::TestWithParam<NamedMaterial> {
 protected:
  std::unique_ptr<cc::Material> material = GetParam().make();
};
INSTANTIATE_TEST_SUITE_P(
    Hex8, Hex8PatchTest,
    ::testing::Values(
        NamedMaterial{"svk", [] { return cc::makeStVenantKirchhoff(kYoung, kPoisson); }},
        NamedMaterial{"neo_hooke", [] { return cc::makeNeoHooke(kYoung, kPoisson); }}),
    [](const auto& info) { return std::string(info.param.name); });

std::vector<Matrix3d> homogeneousDeformations() {
  Matrix3d mild = Matrix3d::Identity();
  mild(0, 1) = 0.02;
  mild(2, 2) = 0.99;
  Matrix3d large;  // stretch 1.5, shear 0.5, lateral contraction
  large << 1.5, 0.5, 0.0, 0.0, 0.9, 0.2, 0.1, 0.0, 0.8;
  return {mild, large};
}

TEST_P(Hex8PatchTest, HomogeneousDeformationIsReproducedExactly) {
  const Patch patch = distortedPatch();
  for (const Matrix3d& F : homogeneousDeformations()) {
    const Eigen::Matrix3Xd current = F * patch.nodes;
    const Matrix3d S = analyticSecondPiola(GetParam().name, F);
    Eigen::Matrix3Xd assembled = Eigen::Matrix3Xd::Zero(3, kPatchNodes);
    for (const auto& element : patch.elements) {
      const cc::Hex8Nodes X = gather(patch.nodes, element);
      const cc::Hex8Nodes x = gather(current, element);
      std::array<cc::Vector6d, cc::kHex8GaussPoints> gaussStress;
      ASSERT_TRUE(cc::hex8GaussPointStresses(X, x, *material, gaussStress).ok());
      for (const cc::Vector6d& stress : gaussStress) {
        EXPECT_LT((cc::stressFromVoigt(stress) - S).norm(), kRoundOff * S.norm());
      }
      const Matrix3d cauchy = F * S * F.transpose() / F.determinant();
      EXPECT_LT((cc::stressFromVoigt(cc::hex8CauchyStress(X, x, *material)) - cauchy).norm(),
                kRoundOff * cauchy.norm());
      cc::Hex8Vector fint;
      ASSERT_TRUE(cc::evaluateHex8(X, x, *material, fint, nullptr).ok());
      for (int a = 0; a < 8; ++a) assembled.col(element[a]) += fint.segment<3>(3 * a);
    }
    const double forceScale = assembled.cwiseAbs().maxCoeff();
    EXPECT_LT(assembled.col(kInteriorNode).norm(), kRoundOff * forceScale);

    // sum_a f_a X_a^T = int P grad(sum_a N_a X_a) dV = P V: the first Piola stress times the
    // patch volume (the distortion keeps the outer boundary the cube [0,2]^3).
    const Matrix3d firstPiolaTimesVolume = assembled * patch.nodes.transpose();
    const Matrix3d expected = F * S * std::pow(kPatchSize, 3);
    EXPECT_LT((firstPiolaTimesVolume - expected).norm(), kRoundOff * expected.norm());
  }
}

}  // namespace
