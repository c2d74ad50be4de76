// Enhanced assumed strains of the solid-shells: the element-level Newton iteration for the EAS
// parameters (static condensation needs the converged local equations R_alpha = 0).
#pragma once

#include <span>

#include "elements/element.hpp"
#include "elements/solid_shell_scheme.hpp"

namespace cc::solidshell {

// What the local iteration needs of one Gauss point, and the stress it leaves there.
struct EasGaussPoint {
  Vector6d compatibleStrain;  // Cartesian Green-Lagrange strain of the (assumed) displacement field
  EasOperator enhancement;    // Cartesian enhanced strain per unit alpha (6 x n_alpha)
  double volume = 0;          // Gauss weight times det J
  Vector6d stress;            // second Piola-Kirchhoff stress at compatible + enhanced strain
  Matrix6d materialTangent;   // dS/dE there
};

// The local equations: R_alpha = sum G^T S dV and K_alpha_alpha = sum G^T D G dV (the enhanced
// strain is linear in alpha, so there is no geometric part).
struct EasSystem {
  EasMatrix stiffness;
  EasVector residual;
};

// Solves R_alpha(alpha) = 0 by Newton's method starting from `alpha` (the warm start; retried
// from zero if that fails), halving steps that leave the material's domain or do not reduce
// the local residual. On success every point holds S and D at the converged alpha and
// `system` the local equations there; the last Newton correction is below round-off of the
// strains, so the result does not depend on the warm start. With no parameters it only
// evaluates the material. Fails with MaterialFailure or LocalIterationFailed.
ElementStatus solveEnhancedStrains(std::span<EasGaussPoint> points, const Material& material,
                                   EasVector& alpha, EasSystem& system);

}  // namespace cc::solidshell
