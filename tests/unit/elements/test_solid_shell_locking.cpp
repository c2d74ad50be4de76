// Locking tests of the solid-shells on thin plate strips in cylindrical bending (plane strain in
// the width direction, so plate theory with D = E t^3 / (12 (1 - nu^2)) is the exact reference):
// a single element of thickness/length 1e-3 under an end moment, and a cantilever strip of
// span/thickness 1000 under a tip force, beside the locking Hex8.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>

#include "elements/solid_shell.hpp"
#include "test_solid_shell_support.hpp"

namespace {

using namespace sstest;

constexpr double kYoung = 1.0e7;
constexpr double kPoisson = 0.3;
constexpr double kLength = 1.0;
constexpr double kWidth = 0.1;
constexpr double kThickness = 1e-3;  // thickness / span = 1e-3
const double kBendingStiffness =
    kYoung * kThickness * kThickness * kThickness / (12 * (1 - kPoisson * kPoisson));

struct StripResult {
  double tipDeflection;  // mean w of the tip nodes
  double tipRotation;    // (u_top - u_bottom) / t at the tip, mean over the width
};

enum class TipLoad { Moment, Force };

// Cantilever strip clamped at x = 0 (u_x = u_z = 0 on both faces), u_y = 0 everywhere (plane
// strain across the width), loaded at x = L by a moment M bending it upwards (face forces -+M/t
// along x on the top/bottom face) or an upward transverse force P, distributed over the width with
// the consistent weights of the element's edge interpolation (1/2 1/2 linear, 1/6 2/3 1/6
// quadratic).
StripResult cantileverStrip(const cc::ElementKernel& element, bool quadratic, int elements,
                            TipLoad load, double magnitude) {
  const ShellMesh mesh = shellMesh(elements, 1, quadratic, [](double u, double v, double s) {
    return Vector3d(u * kLength, v * kWidth, 0.5 * s * kThickness);
  });
  std::vector<bool> fixed(3 * mesh.nodes.cols(), false);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(3 * mesh.nodes.cols());
  const std::vector<double> widthWeights =
      quadratic ? std::vector<double>{1.0 / 6, 2.0 / 3, 1.0 / 6} : std::vector<double>{0.5, 0.5};
  const int tip = mesh.pointsU - 1;
  for (int layer = 0; layer < 2; ++layer) {
    for (int j = 0; j < mesh.pointsV; ++j) {
      for (int i = 0; i < mesh.pointsU; ++i) fixed[3 * mesh.node(i, j, layer) + 1] = true;
      fixed[3 * mesh.node(0, j, layer) + 0] = true;
      fixed[3 * mesh.node(0, j, layer) + 2] = true;
      const int dof = 3 * mesh.node(tip, j, layer);
      if (load == TipLoad::Moment) {
        force[dof + 0] = (layer == 1 ? -1.0 : 1.0) * widthWeights[j] * magnitude / kThickness;
      } else {
        force[dof + 2] = 0.5 * widthWeights[j] * magnitude;
      }
    }
  }
  const auto material = cc::makeStVenantKirchhoff(kYoung, kPoisson);
  const Eigen::VectorXd u = solveLinear(element, *material, mesh, force, fixed);
  StripResult result{0.0, 0.0};
  for (int j = 0; j < mesh.pointsV; ++j) {
    const int bottom = 3 * mesh.node(tip, j, 0), top = 3 * mesh.node(tip, j, 1);
    result.tipDeflection += 0.5 * (u[bottom + 2] + u[top + 2]) / mesh.pointsV;
    result.tipRotation += (u[bottom + 0] - u[top + 0]) / kThickness / mesh.pointsV;
  }
  return result;
}

// Plate theory for the end moment: w = M L^2 / (2 D b), rotation M L / (D b).
StripResult momentReference(double moment) {
  const double curvature = moment / (kBendingStiffness * kWidth);
  return {0.5 * curvature * kLength * kLength, curvature * kLength};
}

// Timoshenko plate strip under a tip force: P L^3 / (3 D b) + P L / (kappa G b t) (the shear
// part is 1e-6 of the total here).
double forceReference(double force) {
  constexpr double kShearCorrection = 5.0 / 6.0;
  const double shearModulus = kYoung / (2 * (1 + kPoisson));
  return force * kLength * kLength * kLength / (3 * kBendingStiffness * kWidth) +
         force * kLength / (kShearCorrection * shearModulus * kWidth * kThickness);
}

// Poisson thickness locking: without an enhanced thickness strain the element cannot stretch
// through the thickness, so it bends with the plane-strain modulus lambda + 2 mu instead of
// E / (1 - nu^2): too stiff by (1 - nu)^2 / (1 - 2 nu).
const double kThicknessLockingRatio = (1 - 2 * kPoisson) / ((1 - kPoisson) * (1 - kPoisson));

// One element reproduces the linear bending state exactly (patch tests), so the end moment gives
// the plate answer up to round-off. That round-off is large for so thin an element: its bending
// stiffness is what remains of transverse shear stiffnesses (L/t)^4 ~ 1e12 times larger, so
// relative errors of about eps (L/t)^4 ~ 2e-4 are inherent (measured: 3e-4 for SolidShell8).
const double kThinElementRoundOff = 10 * kEps * std::pow(kLength / kThickness, 4);

TEST(SolidShellLocking, SingleThinElementBendsLikeAPlate) {
  const double moment = 1.0;
  const StripResult reference = momentReference(moment);
  struct Case {
    const char* name;
    std::unique_ptr<cc::ElementKernel> element;
    bool quadratic;
    double expectedRatio;
  };
  std::vector<Case> cases;
  cases.push_back({"solid_shell8 eas1", cc::makeSolidShell8(1), false, 1.0});
  cases.push_back({"solid_shell8 eas3", cc::makeSolidShell8(3), false, 1.0});
  cases.push_back({"solid_shell8 eas0", cc::makeSolidShell8(0), false, kThicknessLockingRatio});
  cases.push_back({"solid_shell18 eas1", cc::makeSolidShell18(1), true, 1.0});
  cases.push_back({"solid_shell18 eas3", cc::makeSolidShell18(3), true, 1.0});
  cases.push_back({"solid_shell18 eas0", cc::makeSolidShell18(0), true, kThicknessLockingRatio});
  for (const Case& c : cases) {
    const StripResult result = cantileverStrip(*c.element, c.quadratic, 1, TipLoad::Moment, moment);
    const double rotationRatio = result.tipRotation / reference.tipRotation;
    const double deflectionRatio = result.tipDeflection / reference.tipDeflection;
    std::cout << "[ measured ] " << c.name << ": rotation / plate theory = " << rotationRatio
              << ", deflection / plate theory = " << deflectionRatio << '\n';
    EXPECT_NEAR(rotationRatio, c.expectedRatio, kThinElementRoundOff) << c.name;
    EXPECT_NEAR(deflectionRatio, c.expectedRatio, kThinElementRoundOff) << c.name;
  }
  // The plain trilinear hexahedron locks in shear: its bending stiffness is ~ (L/t)^2 too large.
  const StripResult hex8 = cantileverStrip(*cc::makeHex8(), false, 1, TipLoad::Moment, moment);
  const double hex8Ratio = hex8.tipRotation / reference.tipRotation;
  std::cout << "[ measured ] hex8: rotation / plate theory = " << hex8Ratio << '\n';
  EXPECT_LT(hex8Ratio, 1e-4);
}

// Span / thickness 1000, 32 elements along the span: within 1% of the plate strip, while Hex8
// on the same mesh is orders of magnitude too stiff.
TEST(SolidShellLocking, ThinCantileverStripUnderTipForce) {
  constexpr int kElements = 32;
  constexpr double kTolerance = 0.01;
  const double force = 1e-3;
  const double reference = forceReference(force);
  const double shell8 =
      cantileverStrip(*cc::makeSolidShell8(3), false, kElements, TipLoad::Force, force)
          .tipDeflection /
      reference;
  const double shell18 =
      cantileverStrip(*cc::makeSolidShell18(3), true, kElements, TipLoad::Force, force)
          .tipDeflection /
      reference;
  const double hex8 =
      cantileverStrip(*cc::makeHex8(), false, kElements, TipLoad::Force, force).tipDeflection /
      reference;
  std::cout << "[ measured ] tip deflection / plate strip: solid_shell8 " << shell8
            << ", solid_shell18 " << shell18 << ", hex8 " << hex8 << '\n';
  EXPECT_NEAR(shell8, 1.0, kTolerance);
  EXPECT_NEAR(shell18, 1.0, kTolerance);
  EXPECT_LT(hex8, 0.01);
}

}  // namespace

namespace {

// Unit cube of n^3 Hex8-node elements (zeta along z).
sstest::ShellMesh cubeMesh(int n) {
  sstest::ShellMesh mesh;
  mesh.pointsU = mesh.pointsV = n + 1;
  auto node = [n](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
  mesh.nodes.resize(3, (n + 1) * (n + 1) * (n + 1));
  for (int k = 0; k <= n; ++k) {
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) mesh.nodes.col(node(i, j, k)) = Vector3d(i, j, k) / n;
    }
  }
  constexpr std::array<std::array<int, 3>, 8> kCorners = {
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        std::vector<int> element;
        for (const auto& c : kCorners) element.push_back(node(i + c[0], j + c[1], k + c[2]));
        mesh.elements.push_back(element);
      }
    }
  }
  return mesh;
}

// Platen force of a nearly incompressible cube (nu = 0.4999) squeezed by a small displacement
// between rough platens (bottom fixed, top moved down without sliding), linear analysis.
double platenForce(const cc::ElementKernel& element, int n) {
  constexpr double kSqueeze = 1e-3;
  const auto material = cc::makeStVenantKirchhoff(1.0, 0.4999);
  const sstest::ShellMesh mesh = cubeMesh(n);
  const int numDofs = 3 * static_cast<int>(mesh.nodes.cols());
  std::vector<bool> fixed(numDofs, false);
  Eigen::VectorXd prescribed = Eigen::VectorXd::Zero(numDofs);
  for (int a = 0; a < mesh.nodes.cols(); ++a) {
    const bool bottom = mesh.nodes(2, a)<1e-12, top = mesh.nodes(2, a)> 1 - 1e-12;
    for (int c = 0; c < 3; ++c) fixed[3 * a + c] = bottom || top;
    if (top) prescribed[3 * a + 2] = -kSqueeze;
  }
  // Prescribed values enter as the load -K u_p on the free dofs; the platen force is K u there.
  const Eigen::VectorXd free = sstest::solveLinear(
      element, *material, mesh, -sstest::assembleTangentTimes(element, *material, mesh, prescribed),
      fixed);
  const Eigen::VectorXd force =
      sstest::assembleTangentTimes(element, *material, mesh, free + prescribed);
  double platen = 0.0;
  for (int a = 0; a < mesh.nodes.cols(); ++a) {
    if (mesh.nodes(2, a) > 1 - 1e-12) platen -= force[3 * a + 2];
  }
  return platen / kSqueeze;
}

// The solid-shell's enhanced strains (E_33 ~ zeta, E_11 ~ xi, E_22 ~ eta among them) free the
// volumetric constraint that locks the trilinear hexahedron: 4^3 elements are within 10% of
// 8^3 (which is within 3% of 16^3: 1.2775 against 1.2520), while Hex8 is 80 times too stiff.
TEST(SolidShellLocking, NearlyIncompressibleBlockDoesNotLock) {
  const auto shell = cc::makeSolidShell8(7);
  const auto hex8 = cc::makeHex8();
  const double fine = platenForce(*shell, 8);
  const double coarse = platenForce(*shell, 4);
  const double locked = platenForce(*hex8, 4);
  std::cout << "[ measured ] platen stiffness nu = 0.4999: solid_shell8 eas7 4^3 " << coarse
            << ", 8^3 " << fine << "; hex8 4^3 " << locked << '\n';
  EXPECT_NEAR(coarse / fine, 1.0, 0.1);
  EXPECT_GT(locked / fine, 10.0);
}

}  // namespace
