// Solid-shell elements after Hauptmann & Schweizerhof (IJNME 42, 1998; C&S 79, 2001): hexahedra
// with displacement dofs only whose assumed (ANS) and enhanced (EAS) strains remove locking.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <span>
#include <vector>

#include "elements/element.hpp"

// Both elements are total-Lagrangian and take the element's local zeta axis as the thickness
// direction (the model builder orients it with orientThickness()). Strains are interpolated in
// covariant components E_ij = (g_i.g_j - G_i.G_j)/2 of the convective frame, so that the
// assumed fields are independent of the element's orientation and rotation:
//   SolidShell8  (Hex8 nodes, 2x2x2 Gauss points)
//     transverse shear E_13, E_23: sampled at the mid-edges of the mid-surface (Bathe-Dvorkin)
//     thickness strain E_33: sampled at the four corner lines (Betsch-Stein)
//   SolidShell18 (Hex18 nodes: Quad9 at zeta = -1, then at zeta = +1; 3x3x2 Gauss points)
//     transverse shear E_13 (E_23): sampled at xi = +-1/sqrt(3) times eta = 0, +-sqrt(3/5) (and
//     swapped), linear x quadratic interpolation (the MITC9 tying points of Bucalem & Bathe)
//     thickness strain E_33: sampled at the nine node lines, biquadratic interpolation
//     membrane strains E_11, E_22, E_12: MITC9 tying points at the Gauss point's zeta (curved
//     biquadratic elements otherwise lock in membrane: hemisphere 0.28 of the reference at 8x8)
// The enhanced strains (Simo & Rifai) are defined in covariant components at the element centre
// and pushed to the Gauss point with (det J0 / det J) T0, which makes them orthogonal to constant
// stresses (membrane patch test). They are condensed at element level with the consistent
// tangent; the local equations are solved to round-off inside evaluate(), so the element is a
// pure function of its nodal coordinates and the history only warm-starts that iteration.
namespace cc {

// Which assumed-strain ingredients an element uses. The defaults are the locking-free
// formulations; switching an ingredient off exists to show (in tests and verification runs)
// which locking it removes.
struct SolidShellOptions {
  int easParameters = 1;         // see solidShell8EasParameterCounts() / ...18...
  bool assumedShear = true;      // ANS transverse shear (against shear locking)
  bool assumedThickness = true;  // ANS thickness strain (against curvature-thickness locking)
  bool assumedMembrane = true;   // SolidShell18 only: MITC9 membrane strains (membrane locking)
};

// Enhanced-strain parameter counts each element accepts; every mode is linear in zeta or in an
// in-plane coordinate, so it integrates to zero over the element (patch test).
//   SolidShell8:  0 none; 1 E_33 ~ zeta (Poisson thickness locking); 3 E_33 ~ zeta (1, xi, eta)
//                 (exact pure bending with Poisson's ratio on distorted flat elements);
//                 5 = 1 and 7 = 3 plus the membrane modes E_11 ~ xi, E_22 ~ eta, E_12 ~ xi, eta
//                 (in-plane bending, near incompressibility).
//   SolidShell18: 0 none; 1 E_33 ~ zeta; 3 E_33 ~ zeta (1, xi, eta);
//                 9 E_33 ~ zeta times the nine biquadratic monomials.
std::span<const int> solidShell8EasParameterCounts();
std::span<const int> solidShell18EasParameterCounts();

// Throw std::invalid_argument for a parameter count not listed above (the deck layer reports
// the InputError with the deck location before calling these).
std::unique_ptr<ElementKernel> makeSolidShell8(int easParameters);
std::unique_ptr<ElementKernel> makeSolidShell8(const SolidShellOptions& options);
std::unique_ptr<ElementKernel> makeSolidShell18(int easParameters);
std::unique_ptr<ElementKernel> makeSolidShell18(const SolidShellOptions& options);

// Second Piola-Kirchhoff stress (Cartesian Voigt) at each Gauss point with its reference
// position, at the converged EAS parameters: for tests and stress recovery. `element` must come
// from makeSolidShell8/18 (std::invalid_argument otherwise).
struct GaussPointStress {
  Eigen::Vector3d referencePosition;
  Vector6d secondPiola;
};
ElementStatus solidShellGaussPointStresses(const ElementKernel& element, const Eigen::Matrix3Xd& X,
                                           const Eigen::Matrix3Xd& x, const Material& material,
                                           std::vector<GaussPointStress>& stresses);

}  // namespace cc
