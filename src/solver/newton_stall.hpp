// Plain Newton that is not going to converge, told from its residual norms alone (newton.cpp
// ends such an attempt early and the load stepper retries the step with the line search).
// Contact makes the residual piecewise smooth; full Newton steps can then cycle or drift where
// the line search gets through, and every iteration spent before the retry is wasted. Kept
// apart from newton.cpp so that unit tests can feed them histories.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace cc {

// `norms` below: ||rhs|| of each iteration of the attempt so far, the first iteration's first.

// A cycle without any state change: plain Newton alternating between two iterates (or stuck
// at one) whose residual norms repeat (the slip direction of stiffly penalized points flipping
// back and forth; issue 16: 0.267, 0.294, 0.267, ... of the first residual for 30 iterations
// in a press at 100 times the automatic penalty). Two periods of norms equal to
// kCycleNormMatch, checked only while the residual is above kCycleCheckAbove of the first (far
// from the round-off floor and from the small non-smooth stagnations near convergence, which a
// retry would not help).
inline constexpr double kCycleNormMatch = 1e-3;
inline constexpr double kCycleCheckAbove = 1e-3;
// The level below which every test here counts a residual as near convergence.
inline bool nearConvergence(double residual, double reference) {
  return residual <= kCycleCheckAbove * reference;
}
inline bool residualCycles(const std::vector<double>& norms) {
  const std::size_t k = norms.size();
  if (k < 5 || nearConvergence(norms[k - 1], norms[0])) return false;
  auto repeats = [&](std::size_t i) {
    return std::abs(norms[i] - norms[i - 2]) <= kCycleNormMatch * norms[i];
  };
  return repeats(k - 1) && repeats(k - 2);
}

// Plain Newton that has not come below its best residual for kNoProgressIterations iterations
// in a row, still far above convergence, while its energy norm |du . rhs| has not come below its
// best either, is not converging: on example 6.1(a) the one-step press lowered the residual to
// 6e-3 of its first value at iteration 2, then drifted up to 0.12 through 22 iterations of
// stick/slip changes until the residual norms repeated with period 2, its energy norm rising
// with it (2e-5 to 0.15 of the first); the line-search retry converges in 6. Such a step is
// handed to the line search as soon as the drift is plain. The energy norm is the second witness
// because a residual far above its best does not show a drift by itself: a thin strip pressed by
// a stiffly penalised rigid cylinder (`thin_shell_on_cylinder`) opens the points the first
// iterate closed a few at a time, its residual alternating between 7e-2 and 6 of the first for
// ten iterations while the energy norm falls at nearly every one (1e-4 to 3e-6), and plain
// Newton converges in 16; ended on the residual alone, the retry's line search crept at 1/32 of
// the update and the run took 78 steps and 7 cut-backs instead of its 10 steps. Near convergence
// (below kCycleCheckAbove of the step's reference residual) the small non-smooth stagnations
// are left alone, as for the cycles. The reference is the one the convergence test uses: with
// an extrapolating predictor the first iterate's own residual is tiny, and measured against it
// the faceted ironing die's segment hops at 1e-7 of the step's residual (which plain Newton gets
// through in 6-8 iterations) passed for a drift far from convergence; the line search then
// stalled there and the steps were cut back.
inline constexpr std::size_t kNoProgressIterations = 4;
// The index (1-based) of the smallest of values[1 .. k - window - 1] when the last `window`
// values are all above it, else 0. values[0], the first iteration's, is the step's own scale and
// is not a best to compare with.
inline int bestBeforeLast(const std::vector<double>& values, std::size_t window) {
  const std::size_t k = values.size();
  if (k < window + 2) return 0;
  const auto recent = values.end() - static_cast<std::ptrdiff_t>(window);
  const auto best = std::min_element(values.begin() + 1, recent);
  if (!std::all_of(recent, values.end(), [&](double value) { return value > *best; })) return 0;
  return static_cast<int>(best - values.begin()) + 1;
}
// The iteration (1-based) of the best residual when the last kNoProgressIterations were all
// above it, else 0, at any level.
inline int bestBeforeNoProgress(const std::vector<double>& norms) {
  return bestBeforeLast(norms, kNoProgressIterations);
}

// The drift far from convergence: bestBeforeNoProgress while the last residual is above
// kCycleCheckAbove of `reference`, the step's reference residual (Newton's firstResidual), and
// the energy norms of the iterations solved in that window (`energies`: |du_k . rhs_k| of
// iterations 1 .. k - 1 when `norms` holds iterations 1 .. k, in one unit) all above the best
// energy norm before them.
inline int stoppedImproving(const std::vector<double>& norms, const std::vector<double>& energies,
                            double reference) {
  if (norms.empty() || nearConvergence(norms.back(), reference)) return 0;
  const int best = bestBeforeNoProgress(norms);
  if (best == 0 || bestBeforeLast(energies, kNoProgressIterations - 1) == 0) return 0;
  return best;
}

// The same shape near convergence (at or below kCycleCheckAbove of `reference`) does not end
// the attempt: newton.cpp takes the rest of the attempt's updates through the line search. Two
// kinds of plain attempts stop improving there, and their residual norms cannot tell them
// apart (forty-second session: no threshold on the rise separated them over the convergence
// tables of 407 runs):
// - a stick/slip chatter that drifts: the ironing press on a mesh refined twice, FEAP's
//   predictor, came down to 1.9e-7 of its reference and rose for 19 iterations, tens to
//   hundreds of points changing stick/slip or segment in each, until an iterate folded a slab
//   element; the line-search retry then converged in 10. The coarse ironing press at mu = 0.6
//   stays at 2.5e-7 for all 30 iterations (a period-2 alternation below the cycle test's level);
// - points hopping over a faceted master's edges, which full Newton steps get through in a few
//   more iterations and a retry from the step's start did not (a faceted ironing step cut back
//   three times when this shape failed the attempt).
// Damping the current attempt serves both: where the full update lowers the residual the line
// search takes it whole, so a hop goes on as before, and a chatter is damped from where it
// began instead of after a failed attempt and a restart. Measured (about sixty runs, forty-third
// session, docs/verification/sliding.md): the failed attempts of the refined press fall from
// 87 to 11 iterations, the paper decks keep every count.
inline bool stagnatesNearConvergence(const std::vector<double>& norms, double reference) {
  return !norms.empty() && nearConvergence(norms.back(), reference) &&
         bestBeforeNoProgress(norms) > 0;
}

// An active-set cycle (newton.cpp: the contact points' states and segments return to an earlier
// iterate's) at a residual near convergence (nearConvergence above) is damped where it stands
// as well (Newton::detectStall); above it the attempt ends and the step is retried with the line
// search from its start. Near convergence the retry retraced the attempt: the full updates before
// the cycle pass the line search's test whole, so it paid the attempt's iterations twice (the 6.3
// spiral: eight retries of steps whose plain attempts cycled at iteration 3 at 1.5-3.3e-4, 16
// iterations; the smoothed ironing die's first drag step: a cycle at 2e-6 after 4 iterations,
// then 7 in the retry, now 9 in all). Far from it the retry's line search takes another path
// from the start: damping where the cycle began cost example 6.1(a) 9 more iterations in all (a
// cycle at 1e-2) and `large_slip_step` 9 (at 0.12) (forty-fourth session,
// docs/verification/sliding.md).

}  // namespace cc
