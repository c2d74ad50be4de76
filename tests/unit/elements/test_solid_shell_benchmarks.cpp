// Linear shell benchmarks on structured one-layer meshes, solved about the reference state with
// the elements' tangent: MacNeal-Harder's Scordelis-Lo roof, pinched hemisphere with an 18 deg
// hole and pinched cylinder with rigid diaphragms, against the published reference values.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <numbers>

#include "elements/solid_shell.hpp"
#include "test_solid_shell_support.hpp"

namespace {

using namespace sstest;
constexpr double kDegree = std::numbers::pi / 180.0;

struct ElementChoice {
  const char* name;
  std::function<std::unique_ptr<cc::ElementKernel>()> make;
  bool quadratic;
};

std::vector<bool> noConstraints(const ShellMesh& mesh) {
  return std::vector<bool>(3 * mesh.nodes.cols(), false);
}

// Constrains component c of every node (both faces) on the grid line i = const or j = const.
void constrainLineI(const ShellMesh& mesh, int i, int component, std::vector<bool>& fixed) {
  for (int layer = 0; layer < 2; ++layer) {
    for (int j = 0; j < mesh.pointsV; ++j) fixed[3 * mesh.node(i, j, layer) + component] = true;
  }
}
void constrainLineJ(const ShellMesh& mesh, int j, int component, std::vector<bool>& fixed) {
  for (int layer = 0; layer < 2; ++layer) {
    for (int i = 0; i < mesh.pointsU; ++i) fixed[3 * mesh.node(i, j, layer) + component] = true;
  }
}
// Mean displacement component of the two face nodes above grid point (i, j).
double throughThicknessMean(const ShellMesh& mesh, const Eigen::VectorXd& u, int i, int j,
                            int component) {
  return 0.5 * (u[3 * mesh.node(i, j, 0) + component] + u[3 * mesh.node(i, j, 1) + component]);
}

// Scordelis-Lo roof: R = 25, length 50, 80 deg opening, t = 0.25, E = 4.32e8, nu = 0, weight
// 90 per unit area; quarter model u = axial (midspan to diaphragm), v = angle (crown to free
// edge). Returns the vertical displacement at the midspan of the free edge (ref. 0.3024).
double scordelisLo(const ElementChoice& choice, int n) {
  constexpr double kRadius = 25, kHalfLength = 25, kHalfAngle = 40 * kDegree, kThickness = 0.25;
  const ShellMesh mesh = shellMesh(n, n, choice.quadratic, [&](double u, double v, double s) {
    const double radius = kRadius + 0.5 * s * kThickness, angle = v * kHalfAngle;
    return Vector3d(u * kHalfLength, radius * std::sin(angle), radius * std::cos(angle));
  });
  std::vector<bool> fixed = noConstraints(mesh);
  constrainLineI(mesh, 0, 0, fixed);                 // midspan symmetry
  constrainLineI(mesh, mesh.pointsU - 1, 1, fixed);  // rigid diaphragm
  constrainLineI(mesh, mesh.pointsU - 1, 2, fixed);
  constrainLineJ(mesh, 0, 1, fixed);  // crown symmetry
  const auto material = cc::makeStVenantKirchhoff(4.32e8, 0.0);
  const Eigen::VectorXd force = bodyForce(mesh, Vector3d(0, 0, -90.0 / kThickness));
  const Eigen::VectorXd u = solveLinear(*choice.make(), *material, mesh, force, fixed);
  return -throughThicknessMean(mesh, u, 0, mesh.pointsV - 1, 2);
}

// Pinched hemisphere: R = 10, t = 0.04, E = 6.825e7, nu = 0.3, 18 deg hole at the pole, unit
// radial point loads alternating in and out at the equator every 90 deg; quarter model
// u = azimuth (0..90 deg), v = polar angle (equator up to the hole). Returns the outward radial
// displacement under the outward load (ref. 0.0940).
double pinchedHemisphere(const ElementChoice& choice, int n) {
  constexpr double kRadius = 10, kThickness = 0.04, kHole = 18 * kDegree;
  const ShellMesh mesh = shellMesh(n, n, choice.quadratic, [&](double u, double v, double s) {
    const double radius = kRadius + 0.5 * s * kThickness;
    const double azimuth = u * 90 * kDegree, polar = 90 * kDegree - v * (90 * kDegree - kHole);
    return Vector3d(radius * std::sin(polar) * std::cos(azimuth),
                    radius * std::sin(polar) * std::sin(azimuth), radius * std::cos(polar));
  });
  std::vector<bool> fixed = noConstraints(mesh);
  constrainLineI(mesh, 0, 1, fixed);                        // symmetry plane y = 0
  constrainLineI(mesh, mesh.pointsU - 1, 0, fixed);         // symmetry plane x = 0
  fixed[3 * mesh.node(mesh.pointsU / 2, 0, 0) + 2] = true;  // rigid translation along z
  const auto material = cc::makeStVenantKirchhoff(6.825e7, 0.3);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(3 * mesh.nodes.cols());
  for (int layer = 0; layer < 2; ++layer) {
    force[3 * mesh.node(0, 0, layer) + 0] = 0.5;                  // outward along x
    force[3 * mesh.node(mesh.pointsU - 1, 0, layer) + 1] = -0.5;  // inward along y
  }
  const Eigen::VectorXd u = solveLinear(*choice.make(), *material, mesh, force, fixed);
  return throughThicknessMean(mesh, u, 0, 0, 0);
}

// Pinched cylinder with rigid end diaphragms: R = 300, length 600, t = 3, E = 3e6, nu = 0.3,
// two unit loads pinching at midspan; octant model u = axial (midspan to diaphragm),
// v = angle (load line to the side). Returns the radial displacement under the load
// (ref. 1.8248e-5).
double pinchedCylinder(const ElementChoice& choice, int n) {
  constexpr double kRadius = 300, kHalfLength = 300, kThickness = 3;
  const ShellMesh mesh = shellMesh(n, n, choice.quadratic, [&](double u, double v, double s) {
    const double radius = kRadius + 0.5 * s * kThickness, angle = v * 90 * kDegree;
    return Vector3d(u * kHalfLength, radius * std::sin(angle), radius * std::cos(angle));
  });
  std::vector<bool> fixed = noConstraints(mesh);
  constrainLineI(mesh, 0, 0, fixed);                 // midspan symmetry
  constrainLineI(mesh, mesh.pointsU - 1, 1, fixed);  // rigid diaphragm
  constrainLineI(mesh, mesh.pointsU - 1, 2, fixed);
  constrainLineJ(mesh, 0, 1, fixed);                 // symmetry plane y = 0
  constrainLineJ(mesh, mesh.pointsV - 1, 2, fixed);  // symmetry plane z = 0
  const auto material = cc::makeStVenantKirchhoff(3e6, 0.3);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(3 * mesh.nodes.cols());
  for (int layer = 0; layer < 2; ++layer) force[3 * mesh.node(0, 0, layer) + 2] = -0.125;
  const Eigen::VectorXd u = solveLinear(*choice.make(), *material, mesh, force, fixed);
  return -throughThicknessMean(mesh, u, 0, 0, 2);
}

// The published references and the acceptance level: 2% at 16 x 16 elements of the modelled
// part for SolidShell8, and at the same number of nodes (8 x 8) for SolidShell18.
constexpr double kScordelisLoReference = 0.3024;
constexpr double kHemisphereReference = 0.0940;
constexpr double kCylinderReference = 1.8248e-5;
constexpr double kBenchmarkTolerance = 0.02;

const ElementChoice kShell8{"solid_shell8", [] { return cc::makeSolidShell8(3); }, false};
const ElementChoice kShell18{"solid_shell18", [] { return cc::makeSolidShell18(3); }, true};
const ElementChoice kHex8{"hex8", [] { return cc::makeHex8(); }, false};

double timed(const std::function<double()>& run, double& seconds) {
  const auto start = std::chrono::steady_clock::now();
  const double value = run();
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return value;
}

void expectWithinTolerance(const char* benchmark, const ElementChoice& choice, int n,
                           double normalized, double seconds) {
  std::cout << "[ measured ] " << benchmark << ' ' << choice.name << ' ' << n << 'x' << n << ": "
            << normalized << " of the reference (" << seconds << " s)\n";
  EXPECT_NEAR(normalized, 1.0, kBenchmarkTolerance) << benchmark << ' ' << choice.name;
}

TEST(SolidShellBenchmarks, ScordelisLoRoof) {
  double seconds = 0;
  double value = timed([] { return scordelisLo(kShell8, 16); }, seconds);
  expectWithinTolerance("Scordelis-Lo", kShell8, 16, value / kScordelisLoReference, seconds);
  value = timed([] { return scordelisLo(kShell18, 8); }, seconds);
  expectWithinTolerance("Scordelis-Lo", kShell18, 8, value / kScordelisLoReference, seconds);
  const double locked = scordelisLo(kHex8, 16) / kScordelisLoReference;
  std::cout << "[ measured ] Scordelis-Lo hex8 16x16: " << locked << " of the reference\n";
  EXPECT_LT(locked, 0.5);
}

TEST(SolidShellBenchmarks, PinchedHemisphere) {
  double seconds = 0;
  double value = timed([] { return pinchedHemisphere(kShell8, 16); }, seconds);
  expectWithinTolerance("hemisphere", kShell8, 16, value / kHemisphereReference, seconds);
  value = timed([] { return pinchedHemisphere(kShell18, 8); }, seconds);
  expectWithinTolerance("hemisphere", kShell18, 8, value / kHemisphereReference, seconds);
  // Without the MITC9 membrane tying the curved quadratic element locks in membrane.
  cc::SolidShellOptions compatibleMembrane;
  compatibleMembrane.easParameters = 3;
  compatibleMembrane.assumedMembrane = false;
  const ElementChoice locking{"solid_shell18 without membrane ANS",
                              [&] { return cc::makeSolidShell18(compatibleMembrane); }, true};
  const double locked = pinchedHemisphere(locking, 8) / kHemisphereReference;
  std::cout << "[ measured ] hemisphere solid_shell18 without membrane ANS 8x8: " << locked
            << " of the reference\n";
  EXPECT_LT(locked, 0.5);
}

// The pinched cylinder is the hardest of the three for bilinear shells (MITC4 reaches about
// 0.93 at 16 x 16): SolidShell8 needs 32 x 32 for 2%, SolidShell18 meets it at 16 x 16.
TEST(SolidShellBenchmarks, PinchedCylinderWithRigidDiaphragms) {
  double seconds = 0;
  double value = timed([] { return pinchedCylinder(kShell8, 32); }, seconds);
  expectWithinTolerance("pinched cylinder", kShell8, 32, value / kCylinderReference, seconds);
  value = timed([] { return pinchedCylinder(kShell18, 16); }, seconds);
  expectWithinTolerance("pinched cylinder", kShell18, 16, value / kCylinderReference, seconds);
  const double coarse = pinchedCylinder(kShell8, 16) / kCylinderReference;
  std::cout << "[ measured ] pinched cylinder solid_shell8 16x16: " << coarse
            << " of the reference\n";
}

}  // namespace
