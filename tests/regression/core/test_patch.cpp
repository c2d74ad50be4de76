// Patch tests of the whole solver (deck -> gmsh mesh -> model -> Newton load stepping) on a
// distorted Hex8 cube: a homogeneous stretch and a homogeneous shear at large strain (St.
// Venant-Kirchhoff and neo-Hooke) and a rigid rotation by 90 degrees, each prescribed on the
// boundary nodes only. The interior nodes must follow the homogeneous field and every element must
// carry the analytic Cauchy stress, to round-off.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core_decks.hpp"
#include "deck_runner.hpp"

namespace {

using cc::test::coreDeckPath;
using cc::test::DeckRun;
using cc::test::RecordedStep;
using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kMachineEpsilon = std::numeric_limits<double>::epsilon();
// Round-off bound, relative to the scale of the compared field. The interior displacements come
// from solving K du = r on a 4 x 4 x 4 distorted mesh (condition number of order 1e2) whose
// entries sum 8 elements x 8 Gauss points per node, and the stress is computed from them through
// F = I + grad u: a few hundred machine epsilons at most. Measured: displacements 1-5 eps, stress
// 5-40 eps. A formulation error (wrong B matrix on distorted elements, non-objective strain)
// shows up at 1e-3 or more.
constexpr double kRoundoff = 1e3 * kMachineEpsilon;

// The decks' material: E = 100, nu = 0.3 (patch_*.deck, rigid_rotation.deck).
constexpr double kYoungsModulus = 100;
constexpr double kPoissonRatio = 0.3;
constexpr const char* kBoundarySet = "boundary";

struct Lame {
  double lambda;
  double mu;
};

Lame lameOf(double youngsModulus, double poissonRatio) {
  return {youngsModulus * poissonRatio / ((1 + poissonRatio) * (1 - 2 * poissonRatio)),
          youngsModulus / (2 * (1 + poissonRatio))};
}

// sigma = F S F^T / J with S = lambda tr(E) I + 2 mu E, E = (F^T F - I) / 2.
Matrix3d stVenantKirchhoffCauchy(const Matrix3d& F, Lame lame) {
  const Matrix3d greenStrain = 0.5 * (F.transpose() * F - Matrix3d::Identity());
  const Matrix3d secondPiola =
      lame.lambda * greenStrain.trace() * Matrix3d::Identity() + 2 * lame.mu * greenStrain;
  return F * secondPiola * F.transpose() / F.determinant();
}

// Compressible neo-Hooke in the spatial form (Bonet & Wood, eq. 5.29):
// sigma = mu / J (b - I) + lambda ln J / J I with b = F F^T. The program evaluates the
// reference form S = mu (I - C^-1) + lambda ln J C^-1, so this is an independent expression.
Matrix3d neoHookeCauchy(const Matrix3d& F, Lame lame) {
  const double J = F.determinant();
  const Matrix3d leftCauchyGreen = F * F.transpose();
  return lame.mu / J * (leftCauchyGreen - Matrix3d::Identity()) +
         lame.lambda * std::log(J) / J * Matrix3d::Identity();
}

// Voigt order of the stored stress: xx yy zz xy yz xz.
Matrix3d tensorFromVoigt(const Eigen::Matrix<double, 6, 1>& voigt) {
  Matrix3d tensor;
  tensor << voigt[0], voigt[3], voigt[5], voigt[3], voigt[1], voigt[4], voigt[5], voigt[4],
      voigt[2];
  return tensor;
}

std::vector<int> interiorNodes(const cc::Mesh& mesh) {
  std::vector<bool> onBoundary(mesh.numNodes(), false);
  for (int node : mesh.nodeSets.at(kBoundarySet).nodes) onBoundary[node] = true;
  std::vector<int> interior;
  for (int node = 0; node < mesh.numNodes(); ++node) {
    if (!onBoundary[node]) interior.push_back(node);
  }
  return interior;
}

// Largest |u - (F(t) - I) X| over the interior nodes, relative to the largest |(F(t) - I) X|.
double interiorDisplacementError(const cc::Mesh& mesh, const RecordedStep& step,
                                 const Matrix3d& F) {
  double scale = 0;
  for (int node = 0; node < mesh.numNodes(); ++node) {
    scale = std::max(scale, ((F - Matrix3d::Identity()) * mesh.coordinates.col(node)).norm());
  }
  double error = 0;
  for (int node : interiorNodes(mesh)) {
    const Vector3d exact = (F - Matrix3d::Identity()) * mesh.coordinates.col(node);
    error = std::max(error, (step.displacement.col(node) - exact).norm());
  }
  return error / scale;
}

// Largest |sigma_e - sigma| (Frobenius) over the elements, relative to |sigma|.
double stressError(const RecordedStep& step, const Matrix3d& exactStress) {
  double error = 0;
  for (Eigen::Index element = 0; element < step.stress.cols(); ++element) {
    error = std::max(error, (tensorFromVoigt(step.stress.col(element)) - exactStress).norm());
  }
  return error / exactStress.norm();
}

struct HomogeneousField {
  const char* name;
  const char* deck;
  Matrix3d finalGradient;  // F at t = 1; the decks prescribe u = t (F - I) X
};

struct MaterialVariant {
  const char* name;
  const char* deckLine;
  std::function<Matrix3d(const Matrix3d&, Lame)> cauchy;
};

std::vector<HomogeneousField> homogeneousFields() {
  Matrix3d stretch = Vector3d(1.5, 0.8, 1.2).asDiagonal();
  Matrix3d shear = Matrix3d::Identity();
  shear(0, 1) = 0.8;  // ux = 0.8 y
  shear(2, 0) = 0.4;  // uz = 0.4 x
  return {{"stretch", "patch_stretch.deck", stretch}, {"shear", "patch_shear.deck", shear}};
}

std::vector<MaterialVariant> materials() {
  return {{"svk", "material solid svk E=100 nu=0.3", stVenantKirchhoffCauchy},
          {"neohooke", "material solid neohooke E=100 nu=0.3", neoHookeCauchy}};
}

class HomogeneousPatch : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(HomogeneousPatch, InteriorNodesAndStressesAreExact) {
  const HomogeneousField field = homogeneousFields()[std::get<0>(GetParam())];
  const MaterialVariant material = materials()[std::get<1>(GetParam())];
  const std::string path = coreDeckPath(field.deck);
  const std::string deck =
      cc::test::replaceLine(cc::test::readText(path), "material", material.deckLine);
  const DeckRun run = cc::test::runDeckText(deck, path, /*withStress=*/true);
  ASSERT_EQ(run.summary.outcome, cc::RunSummary::Outcome::Completed) << run.summary.message;
  ASSERT_EQ(run.steps.size(), 2u);
  const cc::Mesh& mesh = run.model->mesh();
  ASSERT_EQ(interiorNodes(mesh).size(), 27u);  // (n - 1)^3 for n = 4: the patch has an inside

  const Lame lame = lameOf(kYoungsModulus, kPoissonRatio);
  for (const RecordedStep& step : run.steps) {
    SCOPED_TRACE("t = " + std::to_string(step.time));
    const Matrix3d F =
        Matrix3d::Identity() + step.time * (field.finalGradient - Matrix3d::Identity());
    const Matrix3d exactStress = material.cauchy(F, lame);
    const double displacementError = interiorDisplacementError(mesh, step, F);
    const double stressDeviation = stressError(step, exactStress);
    std::cout << field.name << " " << material.name << " t=" << step.time << ": displacement error "
              << displacementError / kMachineEpsilon << " eps, stress error "
              << stressDeviation / kMachineEpsilon << " eps\n";
    EXPECT_LE(displacementError, kRoundoff);
    EXPECT_LE(stressDeviation, kRoundoff);
    // A homogeneous stress is in equilibrium: the reactions on the closed boundary sum to zero
    // (relative to the force |sigma| times the unit face area).
    EXPECT_LE(step.setReaction(kBoundarySet).norm(), kRoundoff * exactStress.norm());
  }
}

std::string caseName(const ::testing::TestParamInfo<std::tuple<int, int>>& info) {
  return std::string(homogeneousFields()[std::get<0>(info.param)].name) + "_" +
         materials()[std::get<1>(info.param)].name;
}

INSTANTIATE_TEST_SUITE_P(DistortedHex8, HomogeneousPatch,
                         ::testing::Combine(::testing::Values(0, 1), ::testing::Values(0, 1)),
                         caseName);

// rigid_rotation.deck: 90 degrees * t about (1, 2, 3) / sqrt(14), 10 steps.
Matrix3d rotationAt(double time) {
  const Vector3d axis = Vector3d(1, 2, 3).normalized();
  return Eigen::AngleAxisd(std::numbers::pi / 2 * time, axis).toRotationMatrix();
}

TEST(RigidRotation, NinetyDegreesInTenStepsGivesZeroStressAndReactions) {
  const DeckRun run =
      cc::test::runDeckFile(coreDeckPath("rigid_rotation.deck"), /*withStress=*/true);
  ASSERT_EQ(run.summary.outcome, cc::RunSummary::Outcome::Completed) << run.summary.message;
  ASSERT_EQ(run.steps.size(), 10u);
  EXPECT_DOUBLE_EQ(run.steps.back().time, 1.0);
  const cc::Mesh& mesh = run.model->mesh();
  // Scales of "zero": the stress E would produce at unit strain, and the force of that stress
  // on the unit face area of the cube.
  const double stressScale = kYoungsModulus;
  const double forceScale = kYoungsModulus * 1.0;
  double worstStress = 0, worstReaction = 0;
  for (const RecordedStep& step : run.steps) {
    SCOPED_TRACE("t = " + std::to_string(step.time));
    EXPECT_LE(interiorDisplacementError(mesh, step, rotationAt(step.time)), kRoundoff);
    const double stress = step.stress.cwiseAbs().maxCoeff();
    const double reaction = step.reaction.colwise().norm().maxCoeff();
    EXPECT_LE(stress, kRoundoff * stressScale);
    EXPECT_LE(reaction, kRoundoff * forceScale);
    EXPECT_LE(step.setReaction(kBoundarySet).norm(), kRoundoff * forceScale);
    worstStress = std::max(worstStress, stress);
    worstReaction = std::max(worstReaction, reaction);
  }
  std::cout << "rigid rotation: max |stress| " << worstStress / (kMachineEpsilon * stressScale)
            << " eps E, max |nodal reaction| " << worstReaction / (kMachineEpsilon * forceScale)
            << " eps E A\n";
}

}  // namespace
