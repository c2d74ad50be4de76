// SolidShell18: the 18-node solid-shell (Quad9 in-plane, linear in thickness) with MITC9-type
// ANS transverse shear, ANS thickness strain on the node lines and EAS thickness strains.
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "elements/solid_shell.hpp"
#include "elements/solid_shell_element.hpp"
#include "fem/quadrature.hpp"
#include "fem/shape_functions.hpp"

namespace cc {
namespace {

using solidshell::EasMode;
constexpr int kNodes = 18;
constexpr int kInPlaceGauss = 3;    // full integration of the biquadratic field
constexpr int kThicknessGauss = 2;  // full integration of the linear field
constexpr int kGaussPoints = kInPlaceGauss * kInPlaceGauss * kThicknessGauss;
using Scheme = solidshell::AssumedStrainScheme<kNodes, kGaussPoints>;

// The tying points of Bucalem & Bathe's MITC9 shell for the transverse shear E_13: the two
// points of the 2-point rule in xi (where the derivative of a quadratic equals its linear
// interpolant's) times the three points of the 3-point rule in eta. E_23 swaps the roles.
const std::array<double, 2> kLinearTying = {-1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0)};
const std::array<double, 3> kQuadraticTying = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};

void addAssumedShear(Scheme& scheme) {
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double linear = kLinearTying[i];
      const double quadratic = kQuadraticTying[j];
      const int forXiZeta = scheme.addSamplingPoint(Eigen::Vector3d(linear, quadratic, 0.0));
      const int forEtaZeta = scheme.addSamplingPoint(Eigen::Vector3d(quadratic, linear, 0.0));
      for (int g = 0; g < kGaussPoints; ++g) {
        const Eigen::Vector3d& xi = scheme.gaussPoints[g];
        const double weightXiZeta = solidshell::lagrangeWeights(kLinearTying, xi[0])[i] *
                                    solidshell::lagrangeWeights(kQuadraticTying, xi[1])[j];
        const double weightEtaZeta = solidshell::lagrangeWeights(kLinearTying, xi[1])[i] *
                                     solidshell::lagrangeWeights(kQuadraticTying, xi[0])[j];
        scheme.terms[g][solidshell::k13].push_back({forXiZeta, weightXiZeta});
        scheme.terms[g][solidshell::k23].push_back({forEtaZeta, weightEtaZeta});
      }
    }
  }
}

// MITC9 membrane strains (Bucalem & Bathe): E_11 tied at the shear points of E_13, E_22 at those
// of E_23, E_12 at the 2x2 points xi, eta = +-1/sqrt(3); all at the Gauss point's own zeta, since
// the membrane strains vary through the thickness with the bending.
void addAssumedMembrane(Scheme& scheme) {
  const GaussRule1D thickness = gaussLegendre(kThicknessGauss);
  for (double zeta : thickness.points) {
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 3; ++j) {
        const int forXi =
            scheme.addSamplingPoint(Eigen::Vector3d(kLinearTying[i], kQuadraticTying[j], zeta));
        const int forEta =
            scheme.addSamplingPoint(Eigen::Vector3d(kQuadraticTying[j], kLinearTying[i], zeta));
        for (int g = 0; g < kGaussPoints; ++g) {
          const Eigen::Vector3d& xi = scheme.gaussPoints[g];
          if (xi[2] != zeta) continue;
          scheme.terms[g][solidshell::k11].push_back(
              {forXi, solidshell::lagrangeWeights(kLinearTying, xi[0])[i] *
                          solidshell::lagrangeWeights(kQuadraticTying, xi[1])[j]});
          scheme.terms[g][solidshell::k22].push_back(
              {forEta, solidshell::lagrangeWeights(kLinearTying, xi[1])[i] *
                           solidshell::lagrangeWeights(kQuadraticTying, xi[0])[j]});
        }
      }
    }
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j) {
        const int point =
            scheme.addSamplingPoint(Eigen::Vector3d(kLinearTying[i], kLinearTying[j], zeta));
        for (int g = 0; g < kGaussPoints; ++g) {
          const Eigen::Vector3d& xi = scheme.gaussPoints[g];
          if (xi[2] != zeta) continue;
          scheme.terms[g][solidshell::k12].push_back(
              {point, solidshell::lagrangeWeights(kLinearTying, xi[0])[i] *
                          solidshell::lagrangeWeights(kLinearTying, xi[1])[j]});
        }
      }
    }
  }
}

// Thickness strain E_33 sampled on the nine node lines and interpolated with the Quad9 shape
// functions: the curvature-thickness (trapezoidal) locking analogue of Betsch-Stein's corners.
void addAssumedThickness(Scheme& scheme) {
  const Eigen::Matrix<double, 2, 9> nodes = shape::Quad9::nodeCoordinates();
  for (int a = 0; a < 9; ++a) {
    const int line = scheme.addSamplingPoint(Eigen::Vector3d(nodes(0, a), nodes(1, a), 0.0));
    for (int g = 0; g < kGaussPoints; ++g) {
      const Eigen::Vector2d inPlane = scheme.gaussPoints[g].head<2>();
      scheme.terms[g][solidshell::k33].push_back({line, shape::Quad9::values(inPlane)[a]});
    }
  }
}

Scheme buildScheme(const SolidShellOptions& options) {
  Scheme scheme;
  const GaussRule1D inPlane = gaussLegendre(kInPlaceGauss);
  const GaussRule1D thickness = gaussLegendre(kThicknessGauss);
  int g = 0;
  for (int k = 0; k < kThicknessGauss; ++k) {
    for (int j = 0; j < kInPlaceGauss; ++j) {
      for (int i = 0; i < kInPlaceGauss; ++i) {
        const Eigen::Vector3d xi(inPlane.points[i], inPlane.points[j], thickness.points[k]);
        scheme.setGaussPoint(g++, xi,
                             inPlane.weights[i] * inPlane.weights[j] * thickness.weights[k]);
      }
    }
  }
  if (options.assumedMembrane) {
    addAssumedMembrane(scheme);
  } else {
    for (int k : {solidshell::k11, solidshell::k22, solidshell::k12}) scheme.useCompatible(k);
  }
  if (options.assumedShear) {
    addAssumedShear(scheme);
  } else {
    scheme.useCompatible(solidshell::k13);
    scheme.useCompatible(solidshell::k23);
  }
  if (options.assumedThickness) {
    addAssumedThickness(scheme);
  } else {
    scheme.useCompatible(solidshell::k33);
  }
  scheme.finalize<shape::Hex18>();
  return scheme;
}

constexpr std::array<int, 4> kEasCounts = {0, 1, 3, 9};

// E_33 = zeta times in-plane monomials: the thickness stretch linear in zeta that Poisson's
// ratio couples to bending, which the displacement field (linear in zeta) cannot give.
std::vector<EasMode> easModes(int count) {
  constexpr std::array<std::array<int, 3>, 9> kMonomials = {{{0, 0, 1},
                                                             {1, 0, 1},
                                                             {0, 1, 1},
                                                             {1, 1, 1},
                                                             {2, 0, 1},
                                                             {0, 2, 1},
                                                             {2, 1, 1},
                                                             {1, 2, 1},
                                                             {2, 2, 1}}};
  bool allowed = false;
  for (int candidate : kEasCounts) allowed = allowed || candidate == count;
  if (!allowed) {
    throw std::invalid_argument("solid_shell18 accepts 0, 1, 3 or 9 EAS parameters, got " +
                                std::to_string(count));
  }
  std::vector<EasMode> modes;
  for (int m = 0; m < count; ++m) modes.push_back({solidshell::k33, kMonomials[m]});
  return modes;
}

}  // namespace

std::span<const int> solidShell18EasParameterCounts() {
  return kEasCounts;
}

std::unique_ptr<ElementKernel> makeSolidShell18(const SolidShellOptions& options) {
  using Element = solidshell::SolidShell18Element;
  static_assert(Element::N == kNodes);
  return std::make_unique<Element>(
      "solid_shell18", Element::Kernel(buildScheme(options), easModes(options.easParameters)));
}

std::unique_ptr<ElementKernel> makeSolidShell18(int easParameters) {
  SolidShellOptions options;
  options.easParameters = easParameters;
  return makeSolidShell18(options);
}

}  // namespace cc
