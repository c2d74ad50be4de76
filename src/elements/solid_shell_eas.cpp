// Element-level Newton iteration for the enhanced-strain parameters of the solid-shells.
#include "elements/solid_shell_eas.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <sstream>

namespace cc::solidshell {
namespace {

// Newton converges quadratically, so once a correction changes no strain by more than
// kRelativeStrainTolerance (relative to the largest strain) the next one would be below
// round-off; that correction is applied and the iteration stops. kAbsoluteStrainTolerance is
// the round-off level of Green-Lagrange strains computed from O(1)-conditioned coordinates and
// ends the iteration for (nearly) unstrained elements.
constexpr double kRelativeStrainTolerance = 1e-10;
constexpr double kAbsoluteStrainTolerance = 1e-15;
constexpr int kMaxLocalIterations = 30;
constexpr int kMaxStepHalvings = 12;  // a trial step shrunk 4096-fold is no longer progress

// S and D at every point and the local equations at alpha.
ElementStatus evaluateAt(std::span<EasGaussPoint> points, const Material& material,
                         const EasVector& alpha, EasSystem& system) {
  const int n = static_cast<int>(alpha.size());
  system.stiffness.setZero(n, n);
  system.residual.setZero(n);
  for (std::size_t g = 0; g < points.size(); ++g) {
    EasGaussPoint& point = points[g];
    Vector6d strain = point.compatibleStrain;
    if (n > 0) strain.noalias() += point.enhancement * alpha;
    if (!material.evaluate(strain, point.stress, &point.materialTangent)) {
      return tl::materialFailure(static_cast<int>(g), strain);
    }
    if (n == 0) continue;
    system.residual.noalias() += point.enhancement.transpose() * (point.volume * point.stress);
    // lazyProduct: coefficient-wise products; the general (OpenMP-parallel) GEMM path of
    // Eigen's dynamic-size products costs more than the arithmetic at these sizes.
    const EasOperator weightedDG =
        (point.volume * point.materialTangent).lazyProduct(point.enhancement);
    system.stiffness.noalias() += point.enhancement.transpose().lazyProduct(weightedDG);
  }
  return {};
}

double largestStrain(std::span<const EasGaussPoint> points) {
  double largest = 0.0;
  for (const EasGaussPoint& point : points) {
    largest = std::max(largest, point.compatibleStrain.cwiseAbs().maxCoeff());
  }
  return largest;
}

double largestEnhancedStrainChange(std::span<const EasGaussPoint> points,
                                   const EasVector& correction) {
  double largest = 0.0;
  for (const EasGaussPoint& point : points) {
    largest = std::max(largest, (point.enhancement * correction).cwiseAbs().maxCoeff());
  }
  return largest;
}

ElementStatus localFailure(const std::string& why) {
  return {ElementStatus::Code::LocalIterationFailed, "EAS local iteration: " + why};
}

}  // namespace

namespace {

// Newton's method from alpha. A step is accepted when the material accepts the trial strains and
// the local residual decreases (or the step is already below round-off); otherwise it is halved:
// far from the solution (a poor warm start, nearly incompressible materials) the full step can
// overshoot. `alpha` and `system` hold the last accepted state.
ElementStatus newtonIteration(std::span<EasGaussPoint> points, const Material& material,
                              EasVector& alpha, EasSystem& system) {
  if (ElementStatus status = evaluateAt(points, material, alpha, system); !status.ok()) {
    return status;
  }
  const double tolerance =
      kRelativeStrainTolerance * largestStrain(points) + kAbsoluteStrainTolerance;
  double lastChange = 0.0;
  for (int iteration = 0; iteration < kMaxLocalIterations; ++iteration) {
    const Eigen::FullPivLU<EasMatrix> factorization(system.stiffness);
    if (!factorization.isInvertible()) return localFailure("singular K_alpha_alpha");
    const EasVector correction = -factorization.solve(system.residual);
    if (!correction.allFinite()) return localFailure("non-finite correction");
    lastChange = largestEnhancedStrainChange(points, correction);
    const double residualNorm = system.residual.norm();
    double step = 1.0;
    for (int halving = 0;; ++halving) {
      const EasVector trial = alpha + step * correction;
      const bool admissible = evaluateAt(points, material, trial, system).ok();
      if (admissible && (system.residual.norm() < residualNorm || step * lastChange <= tolerance)) {
        alpha = trial;
        break;
      }
      if (halving == kMaxStepHalvings) {
        evaluateAt(points, material, alpha, system);
        return localFailure("no step along the Newton direction reduces the local residual");
      }
      step *= 0.5;
    }
    if (step == 1.0 && lastChange <= tolerance) return {};
  }
  std::ostringstream message;
  message << "no convergence in " << kMaxLocalIterations
          << " iterations (last enhanced strain change " << lastChange << ")";
  return localFailure(message.str());
}

}  // namespace

ElementStatus solveEnhancedStrains(std::span<EasGaussPoint> points, const Material& material,
                                   EasVector& alpha, EasSystem& system) {
  if (alpha.size() == 0) return evaluateAt(points, material, alpha, system);
  const ElementStatus fromWarmStart = newtonIteration(points, material, alpha, system);
  if (fromWarmStart.ok() || alpha.isZero(0.0)) return fromWarmStart;
  alpha.setZero();  // the warm start may lie outside the law's domain or the convergence basin
  return newtonIteration(points, material, alpha, system);
}

}  // namespace cc::solidshell
