// Solid-shell patch tests on flat one-layer patches (MacNeal-Harder's distorted patch, a regular
// and a skewed grid): homogeneous membrane deformations at large strain and the linear pure-bending
// state of 3D elasticity, both reproduced at every Gauss point.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <iostream>
#include <map>
#include <vector>

#include "elements/solid_shell.hpp"
#include "test_solid_shell_support.hpp"

namespace {

using namespace sstest;
using cc::Vector6d;
using Eigen::Vector2d;

constexpr double kYoung = 1.0e3;
constexpr double kPatchLength = 0.24;  // MacNeal & Harder's patch: 0.24 x 0.12 x 0.001
constexpr double kPatchWidth = 0.12;
constexpr double kPatchThickness = 1e-3;
// Round-off of strains and stresses through Jacobians of aspect ratio ~100 (in-plane size over
// thickness) and the EAS condensation: relative 1e-10 is ~5e5 ulps, far below any
// discretization error (which the tests below show to be 1e-3 and more when present).
constexpr double kPatchRoundOff = 1e-10;

struct Patch {
  Eigen::Matrix3Xd nodes;  // planar node i at the bottom (z = -t/2), i + numPlanar at the top
  std::vector<std::vector<int>> elements;
  int numPlanar = 0;
  std::vector<bool> interior;  // planar node not on the outer rectangle
};

// Flat patch from a quadrilateral mesh of the plane, extruded to z in [-t/2, t/2]. Quadratic
// patches get mid-edge and centre nodes; `curve` moves the interior edges' mid-nodes sideways
// (curved element edges) by that fraction of the edge length.
Patch extrudedPatch(const std::vector<Vector2d>& corners,
                    const std::vector<std::array<int, 4>>& quads, bool quadratic, double curve) {
  std::vector<Vector2d> planar = corners;
  std::map<std::pair<int, int>, int> midNodes;
  std::vector<std::vector<int>> faces;
  // On the outer rectangle (only used for unskewed patches).
  auto onBoundary = [](const Vector2d& p) {
    return std::abs(p.y()) < 1e-12 || std::abs(p.y() - kPatchWidth) < 1e-12 ||
           std::abs(p.x()) < 1e-12 || std::abs(p.x() - kPatchLength) < 1e-12;
  };
  for (const auto& quad : quads) {
    std::vector<int> face(quad.begin(), quad.end());
    if (quadratic) {
      for (int e = 0; e < 4; ++e) {
        const int a = quad[e], b = quad[(e + 1) % 4];
        const auto key = std::minmax(a, b);
        if (!midNodes.count(key)) {
          Vector2d mid = 0.5 * (corners[a] + corners[b]);
          const Vector2d edge = corners[b] - corners[a];
          if (!onBoundary(mid)) mid += curve * Vector2d(-edge.y(), edge.x());
          midNodes[key] = static_cast<int>(planar.size());
          planar.push_back(mid);
        }
        face.push_back(midNodes[key]);
      }
      Vector2d centre = Vector2d::Zero();
      for (int c : quad) centre += 0.25 * corners[c];
      face.push_back(static_cast<int>(planar.size()));
      planar.push_back(centre + Vector2d(0.3, -0.2) * curve * kPatchWidth);
    }
    faces.push_back(face);
  }
  const int numPlanar = static_cast<int>(planar.size());
  Patch patch;
  patch.numPlanar = numPlanar;
  patch.nodes.resize(3, 2 * numPlanar);
  for (int layer = 0; layer < 2; ++layer) {
    for (int i = 0; i < numPlanar; ++i) {
      patch.nodes.col(i + layer * numPlanar) =
          Vector3d(planar[i].x(), planar[i].y(), (layer - 0.5) * kPatchThickness);
    }
  }
  for (const Vector2d& p : planar) patch.interior.push_back(!onBoundary(p));
  for (const auto& face : faces) {
    std::vector<int> element;
    for (int layer = 0; layer < 2; ++layer) {
      for (int node : face) element.push_back(node + layer * numPlanar);
    }
    patch.elements.push_back(element);
  }
  return patch;
}

// MacNeal & Harder's five distorted quadrilaterals, each optionally split into m x m by bilinear
// subdivision (the sub-quads tend to parallelograms as m grows).
Patch macNealHarderPatch(bool quadratic, double curve, int m = 1) {
  const std::vector<Vector2d> outline = {{0, 0},       {0.24, 0},    {0.24, 0.12}, {0, 0.12},
                                         {0.04, 0.02}, {0.18, 0.03}, {0.16, 0.08}, {0.08, 0.08}};
  const std::vector<std::array<int, 4>> coarse = {
      {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}};
  std::vector<Vector2d> corners;
  auto nodeAt = [&corners](const Vector2d& p) {
    for (std::size_t i = 0; i < corners.size(); ++i) {
      if ((corners[i] - p).norm() < 1e-12) return static_cast<int>(i);
    }
    corners.push_back(p);
    return static_cast<int>(corners.size()) - 1;
  };
  std::vector<std::array<int, 4>> quads;
  for (const auto& quad : coarse) {
    auto point = [&](int i, int j) {
      const double s = double(i) / m, t = double(j) / m;
      return Vector2d((1 - s) * (1 - t) * outline[quad[0]] + s * (1 - t) * outline[quad[1]] +
                      s * t * outline[quad[2]] + (1 - s) * t * outline[quad[3]]);
    };
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < m; ++i) {
        quads.push_back({nodeAt(point(i, j)), nodeAt(point(i + 1, j)), nodeAt(point(i + 1, j + 1)),
                         nodeAt(point(i, j + 1))});
      }
    }
  }
  return extrudedPatch(corners, quads, quadratic, curve);
}

// 2 x 2 grid of rectangles or, with skew = 0.5, of parallelograms (x += skew y).
Patch gridPatch(bool quadratic, double skew) {
  std::vector<Vector2d> corners;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      const double y = 0.5 * j * kPatchWidth;
      corners.emplace_back(0.5 * i * kPatchLength + skew * y, y);
    }
  }
  const std::vector<std::array<int, 4>> quads = {
      {0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 7, 6}, {4, 5, 8, 7}};
  return extrudedPatch(corners, quads, quadratic, 0.0);
}

struct ElementCase {
  const char* name;
  bool quadratic;
  int easParameters;
  bool assumedMembrane = true;  // SolidShell18: MITC9 membrane tying
};
void PrintTo(const ElementCase& c, std::ostream* out) {
  *out << c.name;
}

std::unique_ptr<cc::ElementKernel> makeElement(const ElementCase& c) {
  cc::SolidShellOptions options;
  options.easParameters = c.easParameters;
  options.assumedMembrane = c.assumedMembrane;
  return c.quadratic ? cc::makeSolidShell18(options) : cc::makeSolidShell8(options);
}

// The two laws written out from their definitions, independently of the library.
Matrix3d analyticSecondPiola(const std::string& law, const Matrix3d& F, double nu) {
  const double lambda = kYoung * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu = kYoung / (2 * (1 + nu));
  const Matrix3d C = F.transpose() * F;
  const Matrix3d I = Matrix3d::Identity();
  if (law == "svk") {
    const Matrix3d E = 0.5 * (C - I);
    return lambda * E.trace() * I + 2 * mu * E;
  }
  const Matrix3d Cinv = C.inverse();
  return mu * (I - Cinv) + lambda * std::log(F.determinant()) * Cinv;
}

class SolidShellPatchTest : public ::testing::TestWithParam<ElementCase> {};
INSTANTIATE_TEST_SUITE_P(
    Elements, SolidShellPatchTest,
    ::testing::Values(ElementCase{"shell8_eas1", false, 1}, ElementCase{"shell8_eas3", false, 3},
                      ElementCase{"shell8_eas7", false, 7}, ElementCase{"shell18_eas1", true, 1},
                      ElementCase{"shell18_eas3", true, 3}, ElementCase{"shell18_eas9", true, 9},
                      ElementCase{"shell18_eas3_compatible_membrane", true, 3, false}),
    [](const auto& info) { return std::string(info.param.name); });

// Whether the element is expected to pass the membrane patch test on a distorted patch: the
// MITC9 membrane tying of SolidShell18 reproduces homogeneous stresses only on straight-edged
// elements and balances them only on parallelograms (its covariant tying interpolates strains
// whose virtual variations are cubic in the tied direction; Panasz & Wisniewski's MITC9i
// addresses this).
bool passesDistortedMembranePatch(const ElementCase& c) {
  return !(c.quadratic && c.assumedMembrane);
}

struct MembranePatchResult {
  double stressError = 0;  // max over Gauss points |S - S(F)| / |S(F)|
  double cauchyError = 0;  // max over elements of the averaged Cauchy stress error
  double forceError = 0;   // max interior column force / largest nodal force
};

// Every node moved by x = F X: the stress must be S(F) at every Gauss point and the Cauchy average
// sigma(F). The top and bottom faces carry the traction P N, so it is the through-thickness
// pair of nodes above an interior point that must be in equilibrium (the shell's in-plane
// equilibrium): the two face tractions cancel on a flat patch of constant thickness.
MembranePatchResult membranePatch(const cc::ElementKernel& element, const Patch& patch,
                                  const NamedMaterial& law, const Matrix3d& F) {
  const auto material = law.make(kYoung, 0.3);
  const Matrix3d S = analyticSecondPiola(law.name, F, 0.3);
  const Matrix3d cauchy = F * S * F.transpose() / F.determinant();
  const Eigen::Matrix3Xd current = F * patch.nodes;
  Eigen::Matrix3Xd assembled = Eigen::Matrix3Xd::Zero(3, patch.nodes.cols());
  MembranePatchResult result;
  for (const auto& connectivity : patch.elements) {
    const Eigen::Matrix3Xd X = gatherNodes(patch.nodes, connectivity);
    const Eigen::Matrix3Xd x = gatherNodes(current, connectivity);
    std::vector<cc::GaussPointStress> stresses;
    EXPECT_TRUE(cc::solidShellGaussPointStresses(element, X, x, *material, stresses).ok());
    for (const auto& point : stresses) {
      result.stressError = std::max(result.stressError,
                                    (cc::stressFromVoigt(point.secondPiola) - S).norm() / S.norm());
    }
    const Matrix3d average = cc::stressFromVoigt(element.cauchyStress(X, x, *material, {}));
    result.cauchyError = std::max(result.cauchyError, (average - cauchy).norm() / cauchy.norm());
    const Eigen::VectorXd fint = internalForce(element, X, x, *material);
    for (std::size_t a = 0; a < connectivity.size(); ++a) {
      assembled.col(connectivity[a]) += fint.segment<3>(3 * a);
    }
  }
  const double forceScale = assembled.cwiseAbs().maxCoeff();
  for (int node = 0; node < patch.numPlanar; ++node) {
    if (!patch.interior[node]) continue;
    const double column = (assembled.col(node) + assembled.col(node + patch.numPlanar)).norm();
    result.forceError = std::max(result.forceError, column / forceScale);
  }
  return result;
}

std::vector<Matrix3d> homogeneousDeformations() {
  Matrix3d membrane = Matrix3d::Identity();  // in-plane stretch and shear, thinning
  membrane.topLeftCorner<2, 2>() << 1.3, 0.25, -0.1, 0.9;
  membrane(2, 2) = 0.85;
  Matrix3d general;  // every component, incl. transverse shear and thickness stretch
  general << 1.5, 0.5, 0.1, 0.0, 0.9, 0.2, 0.1, -0.15, 0.8;
  return {membrane, general};
}

TEST_P(SolidShellPatchTest, MembranePatchOnParallelogramsAtLargeStrain) {
  const auto element = makeElement(GetParam());
  Patch patch = gridPatch(GetParam().quadratic, 0.5);
  patch.interior.assign(patch.numPlanar, false);  // interior: the grid's centre column
  patch.interior[4] = true;
  for (const NamedMaterial& law : {kSvk, kNeoHooke}) {
    for (const Matrix3d& F : homogeneousDeformations()) {
      const MembranePatchResult result = membranePatch(*element, patch, law, F);
      EXPECT_LT(result.stressError, kPatchRoundOff) << law.name;
      EXPECT_LT(result.cauchyError, kPatchRoundOff) << law.name;
      EXPECT_LT(result.forceError, kPatchRoundOff) << law.name;
    }
  }
}

// MacNeal-Harder's distorted patch; quadratic elements also get curved interior edges (mid-nodes
// moved sideways by 2% of the edge length) unless they use the MITC9 membrane tying.
TEST_P(SolidShellPatchTest, MembranePatchOnTheDistortedPatchAtLargeStrain) {
  const auto element = makeElement(GetParam());
  const bool exact = passesDistortedMembranePatch(GetParam());
  const Patch patch = macNealHarderPatch(GetParam().quadratic, exact ? 0.02 : 0.0);
  for (const NamedMaterial& law : {kSvk, kNeoHooke}) {
    for (const Matrix3d& F : homogeneousDeformations()) {
      const MembranePatchResult result = membranePatch(*element, patch, law, F);
      EXPECT_LT(result.stressError, kPatchRoundOff) << law.name;
      EXPECT_LT(result.cauchyError, kPatchRoundOff) << law.name;
      if (exact) {
        EXPECT_LT(result.forceError, kPatchRoundOff) << law.name;
      }
    }
  }
}

// The MITC9 tying passes the patch test only in the weak sense: the interior residual on the
// distorted patch (1.0% and 0.65% of the nodal force scale for the two deformations) shrinks as
// its quadrilaterals are subdivided towards parallelograms (to 0.29% and 0.17% at 8 x 8).
TEST(SolidShell18Patch, Mitc9MembraneResidualVanishesUnderRefinement) {
  constexpr int kRefinement = 8;
  constexpr double kRequiredReduction = 0.5;
  const auto element = makeElement(ElementCase{"shell18_eas3", true, 3});
  for (const Matrix3d& F : homogeneousDeformations()) {
    const double coarse =
        membranePatch(*element, macNealHarderPatch(true, 0.0), kSvk, F).forceError;
    const double fine =
        membranePatch(*element, macNealHarderPatch(true, 0.0, kRefinement), kSvk, F).forceError;
    std::cout << "[ measured ] MITC9 membrane patch residual: " << coarse << " -> " << fine
              << " at " << kRefinement << " x " << kRefinement << " subdivision\n";
    EXPECT_GT(coarse, kPatchRoundOff);  // the documented limitation is still there
    EXPECT_LT(fine, kRequiredReduction * coarse);
  }
}

// The linear pure-bending state of 3D elasticity, sigma_xx = a z, sigma_yy = b z, sigma_xy = c z
// and all else zero, has the exact displacement field
//   u = (k1 x + k12 y / 2) z,  v = (k2 y + k12 x / 2) z,
//   w = -(k1 x^2 + k2 y^2 + k12 x y) / 2 + k3 z^2 / 2
// with k1 = (a - nu b)/E, k2 = (b - nu a)/E, k12 = 2(1 + nu) c/E, k3 = -nu (a + b)/E. Imposed on
// every node it is reproduced if the transverse shear (mid-edge/tying-point sampling, exact for
// the quadratic w along straight edges) and the thickness stretch k3 z (EAS) come out right.
// The amplitude (a = E: rotations w_x ~ 0.24) does not matter for the odd-part linearization
// below, and a large one keeps u resolved in x = X + u (relative eps |X| / |u| ~ 1e-15).
struct BendingState {
  double a = kYoung, b = 0.5 * kYoung, c = 0.3 * kYoung;
  Vector3d displacement(const Vector3d& p, double nu) const {
    const double k1 = (a - nu * b) / kYoung, k2 = (b - nu * a) / kYoung;
    const double k12 = 2 * (1 + nu) * c / kYoung, k3 = -nu * (a + b) / kYoung;
    const double x = p.x(), y = p.y(), z = p.z();
    return {(k1 * x + 0.5 * k12 * y) * z, (k2 * y + 0.5 * k12 * x) * z,
            -0.5 * (k1 * x * x + k2 * y * y + k12 * x * y) + 0.5 * k3 * z * z};
  }
  Vector6d stress(const Vector3d& p) const {
    Vector6d s = Vector6d::Zero();
    s << a * p.z(), b * p.z(), 0.0, c * p.z(), 0.0, 0.0;
    return s;
  }
};

// Largest Gauss-point deviation from the bending stress, relative to the largest bending
// stress a t/2. The linear response is the odd part of the St. Venant-Kirchhoff response,
// (S(+u) - S(-u)) / 2, exact because E is quadratic and S linear in the displacements.
double bendingPatchError(const cc::ElementKernel& element, const Patch& patch, double nu) {
  const auto material = cc::makeStVenantKirchhoff(kYoung, nu);
  const BendingState bending;
  Eigen::Matrix3Xd displacement(3, patch.nodes.cols());
  for (int n = 0; n < patch.nodes.cols(); ++n) {
    displacement.col(n) = bending.displacement(patch.nodes.col(n), nu);
  }
  double worst = 0.0;
  for (const auto& connectivity : patch.elements) {
    const Eigen::Matrix3Xd X = gatherNodes(patch.nodes, connectivity);
    const Eigen::Matrix3Xd u = gatherNodes(displacement, connectivity);
    std::vector<cc::GaussPointStress> plus, minus;
    EXPECT_TRUE(cc::solidShellGaussPointStresses(element, X, X + u, *material, plus).ok());
    EXPECT_TRUE(cc::solidShellGaussPointStresses(element, X, X - u, *material, minus).ok());
    for (std::size_t g = 0; g < plus.size(); ++g) {
      const Vector6d linear = 0.5 * (plus[g].secondPiola - minus[g].secondPiola);
      const Vector6d expected = bending.stress(plus[g].referencePosition);
      worst = std::max(worst, (linear - expected).cwiseAbs().maxCoeff());
    }
  }
  return worst / (bending.a * 0.5 * kPatchThickness);
}

TEST_P(SolidShellPatchTest, PureBendingIsExactOnRectangularAndSkewedPatches) {
  const auto element = makeElement(GetParam());
  for (double skew : {0.0, 0.5}) {
    const double error = bendingPatchError(*element, gridPatch(GetParam().quadratic, skew), 0.3);
    EXPECT_LT(error, kPatchRoundOff) << "skew " << skew;
  }
}

// On the distorted patch det J varies in-plane, so the pushed-forward thickness mode
// zeta det J0 / det J needs the in-plane linear factors (eas >= 3) to give a uniform thickness
// stretch; with Poisson's ratio 0 no thickness stretch is needed and every variant is exact.
TEST_P(SolidShellPatchTest, PureBendingOnTheDistortedPatch) {
  const auto element = makeElement(GetParam());
  const Patch patch = macNealHarderPatch(GetParam().quadratic, 0.0);
  EXPECT_LT(bendingPatchError(*element, patch, 0.0), kPatchRoundOff);
  const double withPoisson = bendingPatchError(*element, patch, 0.3);
  std::cout << "[ measured ] distorted bending patch, nu = 0.3: max stress error / (a t/2) = "
            << withPoisson << '\n';
  if (GetParam().easParameters >= 3) {
    EXPECT_LT(withPoisson, kPatchRoundOff);
  } else {
    EXPECT_GT(withPoisson, 1e-3);  // the documented limitation of a single thickness mode
  }
}

}  // namespace
