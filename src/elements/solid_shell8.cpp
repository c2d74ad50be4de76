// SolidShell8: the 8-node solid-shell (Hex8 nodes) with Bathe-Dvorkin ANS transverse shear,
// Betsch-Stein ANS thickness strain and EAS thickness (and optionally membrane) strains.
#include <array>
#include <stdexcept>
#include <string>

#include "elements/solid_shell.hpp"
#include "elements/solid_shell_element.hpp"
#include "fem/quadrature.hpp"
#include "fem/shape_functions.hpp"

namespace cc {
namespace {

using solidshell::EasMode;
constexpr int kNodes = 8;
constexpr int kGaussPerDirection = 2;  // full integration of the trilinear field
constexpr int kGaussPoints = kGaussPerDirection * kGaussPerDirection * kGaussPerDirection;
using Scheme = solidshell::AssumedStrainScheme<kNodes, kGaussPoints>;

// Transverse shear E_13 (E_23) is sampled where it is free of spurious bending: at the mid-edges
// eta = -1, +1 (xi = -1, +1) of the mid-surface, and interpolated linearly across the element.
void addAssumedShear(Scheme& scheme) {
  constexpr std::array<double, 2> kEdges = {-1.0, 1.0};
  for (double edge : kEdges) {
    const int alongXi = scheme.addSamplingPoint(Eigen::Vector3d(0.0, edge, 0.0));
    const int alongEta = scheme.addSamplingPoint(Eigen::Vector3d(edge, 0.0, 0.0));
    for (int g = 0; g < kGaussPoints; ++g) {
      const Eigen::Vector3d& xi = scheme.gaussPoints[g];
      scheme.terms[g][solidshell::k13].push_back({alongXi, 0.5 * (1.0 + edge * xi[1])});
      scheme.terms[g][solidshell::k23].push_back({alongEta, 0.5 * (1.0 + edge * xi[0])});
    }
  }
}

// Thickness strain E_33 sampled on the four corner lines (where a trapezoidal cross-section
// has no spurious thickness strain in bending) and interpolated bilinearly in-plane.
void addAssumedThickness(Scheme& scheme) {
  const Eigen::Matrix<double, 2, 4> corners = shape::Quad4::nodeCoordinates();
  for (int c = 0; c < 4; ++c) {
    const int line = scheme.addSamplingPoint(Eigen::Vector3d(corners(0, c), corners(1, c), 0.0));
    for (int g = 0; g < kGaussPoints; ++g) {
      const Eigen::Vector2d inPlane = scheme.gaussPoints[g].head<2>();
      scheme.terms[g][solidshell::k33].push_back({line, shape::Quad4::values(inPlane)[c]});
    }
  }
}

Scheme buildScheme(const SolidShellOptions& options) {
  Scheme scheme;
  const auto gauss = gaussHexFixed<kGaussPerDirection>();
  for (int g = 0; g < kGaussPoints; ++g) scheme.setGaussPoint(g, gauss[g].xi, gauss[g].weight);
  for (int k : {solidshell::k11, solidshell::k22, solidshell::k12}) scheme.useCompatible(k);
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
  scheme.finalize<shape::Hex8>();
  return scheme;
}

constexpr std::array<int, 5> kEasCounts = {0, 1, 3, 5, 7};

std::vector<EasMode> easModes(int count) {
  // E_33 linear in zeta: the thickness stretch that bending with Poisson's ratio needs and the
  // displacement field (linear in zeta) cannot give (Poisson thickness locking). Its in-plane
  // linear variants make the pushed-forward mode (det J0 / det J) zeta (a + b xi + c eta) able
  // to follow a constant Cartesian thickness stretch on any flat bilinear element, whose det J
  // is linear in xi and eta.
  const std::array<EasMode, 3> thickness = {
      {{solidshell::k33, {0, 0, 1}}, {solidshell::k33, {1, 0, 1}}, {solidshell::k33, {0, 1, 1}}}};
  // Simo-Rifai membrane modes: in-plane bending without parasitic in-plane shear.
  const std::array<EasMode, 4> membrane = {{{solidshell::k11, {1, 0, 0}},
                                            {solidshell::k22, {0, 1, 0}},
                                            {solidshell::k12, {1, 0, 0}},
                                            {solidshell::k12, {0, 1, 0}}}};
  const int thicknessModes = count == 3 || count == 7 ? 3 : (count == 0 ? 0 : 1);
  const bool withMembrane = count == 5 || count == 7;
  bool allowed = false;
  for (int candidate : kEasCounts) allowed = allowed || candidate == count;
  if (!allowed) {
    throw std::invalid_argument("solid_shell8 accepts 0, 1, 3, 5 or 7 EAS parameters, got " +
                                std::to_string(count));
  }
  std::vector<EasMode> modes(thickness.begin(), thickness.begin() + thicknessModes);
  if (withMembrane) modes.insert(modes.end(), membrane.begin(), membrane.end());
  return modes;
}

}  // namespace

std::span<const int> solidShell8EasParameterCounts() {
  return kEasCounts;
}

std::unique_ptr<ElementKernel> makeSolidShell8(const SolidShellOptions& options) {
  using Element = solidshell::SolidShell8Element;
  static_assert(Element::N == kNodes);
  return std::make_unique<Element>(
      "solid_shell8", Element::Kernel(buildScheme(options), easModes(options.easParameters)));
}

std::unique_ptr<ElementKernel> makeSolidShell8(int easParameters) {
  SolidShellOptions options;
  options.easParameters = easParameters;
  return makeSolidShell8(options);
}

}  // namespace cc
