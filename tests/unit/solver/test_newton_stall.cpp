// The residual-history tests that end a plain Newton attempt early (newton_stall.hpp), on
// histories recorded from runs or shaped like them.
#include <gtest/gtest.h>

#include <vector>

#include "solver/newton_stall.hpp"

namespace cc {
namespace {

// The first iteration (1-based) at which the test fires on a prefix of `norms`, 0 if never.
template <typename Test>
int firstFiring(const std::vector<double>& norms, Test test) {
  for (std::size_t k = 1; k <= norms.size(); ++k) {
    if (test(std::vector<double>(norms.begin(), norms.begin() + static_cast<long>(k)))) {
      return static_cast<int>(k);
    }
  }
  return 0;
}

// `energies` holds |du . rhs| of every solved iteration of the same attempt: a prefix of k
// residual norms is judged with the first k - 1 energy norms, as newton.cpp has them.
int firstNoProgress(const std::vector<double>& norms, const std::vector<double>& energies) {
  return firstFiring(norms, [&](const std::vector<double>& h) {
    const std::vector<double> solved(energies.begin(),
                                     energies.begin() + static_cast<long>(h.size() - 1));
    return stoppedImproving(h, solved, h[0]) > 0;
  });
}

// The residual alone: where the drift test would fire if the energy norms agreed.
int firstResidualDrift(const std::vector<double>& norms) {
  return firstFiring(norms, [](const std::vector<double>& h) {
    return !nearConvergence(h.back(), h[0]) && bestBeforeNoProgress(h) > 0;
  });
}

int firstCycle(const std::vector<double>& norms) {
  return firstFiring(norms, [](const std::vector<double>& h) { return residualCycles(h); });
}

// Example 6.1(a)'s one-step press (paper mesh, --newton-log of the plain attempt with the drift
// test switched off, fifty-second session), relative residuals and energy norms: down to 6e-3
// and 2e-5 at iteration 2, then both up through stick/slip changes, to 0.12 and 0.15 by
// iteration 24 (the first twelve here). The drift is plain at iteration 6.
const std::vector<double> kExample61Press{1.0,      6.002e-3, 6.325e-3, 1.348e-2,
                                          1.065e-2, 1.697e-2, 2.139e-2, 3.672e-2,
                                          3.921e-2, 5.221e-2, 6.207e-2, 6.230e-2};
const std::vector<double> kExample61PressEnergy{1.0,      1.959e-5, 9.730e-5, 8.883e-5,
                                                8.898e-5, 5.972e-4, 8.410e-4, 5.242e-3,
                                                5.389e-3, 1.684e-2, 1.617e-2, 2.871e-2};

// The thin strip of `thin_shell_on_cylinder` (solid-shells, t = span / 1000, eps_n = 1e9),
// step 1 (--newton-log): the rising cylinder closes 64 points at the first iterate and Newton
// opens them a few at a time, 64 -> 42 -> 24 -> 44 -> 28 -> 20 -> ... -> 2 active; the residual
// alternates far above its best of iteration 3 while the energy norm comes below its best at
// nearly every iteration, and the attempt converges in 16.
const std::vector<double> kThinStripPress{1.0,      79.24,    7.169e-2, 6.091,   1.349e-1, 2.431,
                                          5.732e-1, 1.676,    5.203e-1, 1.181,   4.818e-1, 7.926e-1,
                                          5.082e-2, 2.684e-2, 4.564e-5, 5.392e-8};
const std::vector<double> kThinStripPressEnergy{
    1.0,      1.524e-2, 1.051e-4, 1.873e-4, 4.689e-5, 4.526e-5, 3.156e-5,  3.084e-5,
    2.134e-5, 1.977e-5, 1.407e-5, 3.294e-6, 1.797e-7, 2.004e-9, 2.122e-13, 8.124e-21};

// A stagnation near convergence, shaped like the recorded ones below.
const std::vector<double> kPlateau{1.0, 1e-2, 1e-5, 2e-5, 3e-5, 2e-5, 3e-5, 2e-5, 3e-5};

TEST(NewtonStall, ThePressOfExample61StopsImprovingAtIterationSix) {
  const std::vector<double>& press = kExample61Press;
  EXPECT_EQ(firstNoProgress(press, kExample61PressEnergy), 6);
  EXPECT_EQ(firstResidualDrift(press), 6);
  const std::vector<double> firstSix(press.begin(), press.begin() + 6);
  const std::vector<double> firstFiveEnergies(kExample61PressEnergy.begin(),
                                              kExample61PressEnergy.begin() + 5);
  EXPECT_EQ(stoppedImproving(firstSix, firstFiveEnergies, 1.0), 2);
  EXPECT_EQ(firstCycle(press), 0);
}

// A residual that alternates far above its best is no drift while the energy norm still comes
// below its best: the thin strip's press, which the residual alone would have ended at
// iteration 7 (the retry's line search then crept at 1/32 of the update, 7 cut-backs followed).
TEST(NewtonStall, AnAttemptWhoseEnergyNormStillFallsIsNotEnded) {
  EXPECT_EQ(firstResidualDrift(kThinStripPress), 7);
  EXPECT_EQ(firstNoProgress(kThinStripPress, kThinStripPressEnergy), 0);
  // The same residuals with an energy norm that stops falling after iteration 3 do end it.
  std::vector<double> energyStops = kThinStripPressEnergy;
  for (std::size_t k = 3; k < energyStops.size(); ++k) energyStops[k] = 2 * energyStops[2];
  EXPECT_EQ(firstNoProgress(kThinStripPress, energyStops), 7);
}

// Converging histories never fire: a first iterate far off (example 6.1(a) step 2), and a
// residual that rises for three iterations of active-set changes and then comes below its best.
TEST(NewtonStall, ConvergingHistoriesDoNotFire) {
  const std::vector<double> bumpThenQuadratic{1.0, 0.927, 4.564e-5, 2.779e-8, 1e-14};
  const std::vector<double> threeUpThenDown{1.0, 1e-2, 2e-2, 4e-2, 3e-2, 8e-3, 1e-4, 1e-8};
  EXPECT_EQ(firstResidualDrift(bumpThenQuadratic), 0);
  EXPECT_EQ(firstResidualDrift(threeUpThenDown), 0);
  EXPECT_EQ(firstCycle(bumpThenQuadratic), 0);
  EXPECT_EQ(firstCycle(threeUpThenDown), 0);
}

// Near convergence (below 1e-3 of the first residual) a stagnation does not end the attempt: a
// retry from the step's start would throw away an iterate close to the solution (the attempt
// is damped instead: the next test).
TEST(NewtonStall, AStagnationNearConvergenceDoesNotFire) {
  EXPECT_EQ(firstResidualDrift(kPlateau), 0);
  EXPECT_EQ(firstCycle(kPlateau), 0);
}

// The same plateau is where the rest of the attempt goes through the line search
// (stagnatesNearConvergence): the ironing press at mu = 0.6, NTS, step 4 (--newton-log), whose
// plain attempt alternated like this for all 30 iterations. Not above 1e-3 of the reference,
// where the attempt is ended instead, and not while the residual still comes below its best.
int firstStagnation(const std::vector<double>& norms, double reference) {
  return firstFiring(norms, [reference](const std::vector<double>& h) {
    return stagnatesNearConvergence(h, reference);
  });
}

TEST(NewtonStall, APlateauNearConvergenceIsDampedFromTheFourthIterationAboveItsBest) {
  const std::vector<double> press{1.0,      1.254e-5, 2.648e-7, 2.928e-7, 2.433e-7,
                                  2.795e-7, 2.637e-7, 2.673e-7, 2.781e-7, 2.585e-7};
  EXPECT_EQ(firstStagnation(press, 1.0), 9);
  EXPECT_EQ(firstResidualDrift(press), 0);
  EXPECT_EQ(firstStagnation(kPlateau, 1.0), 7);
  EXPECT_EQ(firstStagnation(kExample61Press, 1.0), 0);  // far from convergence: ended instead
  const std::vector<double> threeUpThenDown{1.0, 1e-5, 2e-5, 4e-5, 3e-5, 8e-6, 1e-7, 1e-11};
  EXPECT_EQ(firstStagnation(threeUpThenDown, 1.0), 0);
}

// With an extrapolating predictor the first iterate's own residual is tiny and the step's
// reference is the predicted increment's force: the faceted ironing die, STS, mu = 0, step 13
// (residuals relative to that reference, --newton-log): segment hops keep the residual near
// 1e-7 for five iterations, then it converges. Far below 1e-3 of the reference: no drift.
TEST(NewtonStall, SegmentHopsNearConvergenceAfterAPredictorDoNotFire) {
  const std::vector<double> hops{6.835e-7, 1.183e-7, 1.717e-7, 1.243e-7,
                                 1.517e-7, 1.949e-7, 2.950e-9, 4.669e-14};
  // An energy norm that rises at every iteration: no progress by it at all.
  auto risingEnergies = [](std::size_t solved) {
    std::vector<double> energies(solved);
    for (std::size_t k = 0; k < solved; ++k) energies[k] = 1.0 + static_cast<double>(k);
    return energies;
  };
  for (std::size_t k = 1; k <= hops.size(); ++k) {
    const std::vector<double> prefix(hops.begin(), hops.begin() + static_cast<long>(k));
    EXPECT_EQ(stoppedImproving(prefix, risingEnergies(k - 1), 1.0), 0);
  }
  // Measured against the first iterate's own residual it would have fired at iteration 6.
  const std::vector<double> firstSix(hops.begin(), hops.begin() + 6);
  EXPECT_EQ(stoppedImproving(firstSix, risingEnergies(5), hops[0]), 2);
}

// A period-2 cycle whose low iterate is the best so far is no drift above the best: the cycle
// test is the one that sees it (the stiff press of issue 16: 0.267, 0.294, 0.267, ...).
TEST(NewtonStall, APeriodTwoCycleThroughTheBestIterateIsTheCycleTestsToFind) {
  const std::vector<double> cycle{1.0, 0.5, 0.267, 0.294, 0.267, 0.294, 0.267, 0.294, 0.267};
  EXPECT_EQ(firstCycle(cycle), 6);
  EXPECT_EQ(firstResidualDrift(cycle), 0);
}

}  // namespace
}  // namespace cc
