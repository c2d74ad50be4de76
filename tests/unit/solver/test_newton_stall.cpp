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

int firstNoProgress(const std::vector<double>& norms) {
  return firstFiring(norms,
                     [](const std::vector<double>& h) { return stoppedImproving(h, h[0]) > 0; });
}

int firstCycle(const std::vector<double>& norms) {
  return firstFiring(norms, [](const std::vector<double>& h) { return residualCycles(h); });
}

// Example 6.1(a)'s one-step press (paper mesh, --newton-log), relative residuals of the plain
// attempt: down to 3e-3 at iteration 2, then up through stick/slip changes. The period-2 test
// stopped it at iteration 25; the drift is plain at iteration 6.
const std::vector<double> kExample61Press{1.0,      2.977e-3, 3.755e-3, 9.558e-3,
                                          9.235e-3, 2.706e-2, 2.869e-2, 3.275e-2,
                                          3.879e-2, 3.683e-2, 3.784e-2};

// A stagnation near convergence, shaped like the recorded ones below.
const std::vector<double> kPlateau{1.0, 1e-2, 1e-5, 2e-5, 3e-5, 2e-5, 3e-5, 2e-5, 3e-5};

TEST(NewtonStall, ThePressOfExample61StopsImprovingAtIterationSix) {
  const std::vector<double>& press = kExample61Press;
  EXPECT_EQ(firstNoProgress(press), 6);
  EXPECT_EQ(stoppedImproving(std::vector<double>(press.begin(), press.begin() + 6), 1.0), 2);
  EXPECT_EQ(firstCycle(press), 0);
}

// Converging histories never fire: a first iterate far off (example 6.1(a) step 2), and a
// residual that rises for three iterations of active-set changes and then comes below its best.
TEST(NewtonStall, ConvergingHistoriesDoNotFire) {
  const std::vector<double> bumpThenQuadratic{1.0, 0.927, 4.564e-5, 2.779e-8, 1e-14};
  const std::vector<double> threeUpThenDown{1.0, 1e-2, 2e-2, 4e-2, 3e-2, 8e-3, 1e-4, 1e-8};
  EXPECT_EQ(firstNoProgress(bumpThenQuadratic), 0);
  EXPECT_EQ(firstNoProgress(threeUpThenDown), 0);
  EXPECT_EQ(firstCycle(bumpThenQuadratic), 0);
  EXPECT_EQ(firstCycle(threeUpThenDown), 0);
}

// Near convergence (below 1e-3 of the first residual) a stagnation does not end the attempt: a
// retry from the step's start would throw away an iterate close to the solution (the attempt
// is damped instead: the next test).
TEST(NewtonStall, AStagnationNearConvergenceDoesNotFire) {
  EXPECT_EQ(firstNoProgress(kPlateau), 0);
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
  EXPECT_EQ(firstNoProgress(press), 0);
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
  for (std::size_t k = 1; k <= hops.size(); ++k) {
    EXPECT_EQ(stoppedImproving(std::vector<double>(hops.begin(), hops.begin() + k), 1.0), 0);
  }
  // Measured against the first iterate's own residual it would have fired at iteration 6.
  EXPECT_EQ(stoppedImproving(std::vector<double>(hops.begin(), hops.begin() + 6), hops[0]), 2);
}

// A period-2 cycle whose low iterate is the best so far is no drift above the best: the cycle
// test is the one that sees it (the stiff press of issue 16: 0.267, 0.294, 0.267, ...).
TEST(NewtonStall, APeriodTwoCycleThroughTheBestIterateIsTheCycleTestsToFind) {
  const std::vector<double> cycle{1.0, 0.5, 0.267, 0.294, 0.267, 0.294, 0.267, 0.294, 0.267};
  EXPECT_EQ(firstCycle(cycle), 6);
  EXPECT_EQ(firstNoProgress(cycle), 0);
}

}  // namespace
}  // namespace cc
