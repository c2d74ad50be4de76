// Quadratic convergence of Newton's method on a hyperelastic problem at large deformation (a
// neo-Hooke cantilever bent by a tip displacement of L/2 in 4 steps): from the logged residual
// norms, r_{k+1} / r_k^2 stays bounded over the last iterations of every step, i.e. the assembled
// tangent is the consistent linearization of the residual. A negative control shows that the same
// check rejects a linearly converging history.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <limits>
#include <vector>

#include "core_decks.hpp"
#include "deck_runner.hpp"

namespace {

// A residual below this fraction of the step's first residual is round-off: r_1 (the out-of-
// balance force of the prescribed increment, K_fp du_p) is the force scale of the step, and the
// assembled residual sums element forces of that size with relative errors of a few hundred
// machine epsilons (the solver's own round-off rule, kRoundoffResidual, uses 1e3 eps too).
constexpr double kRoundoffFloor = 1e3 * std::numeric_limits<double>::epsilon();
// The quadratic ratio is an upper bound, reached or not depending on the direction of the error,
// so the largest ratio of a step scatters around the problem's Newton constant by about an order
// of magnitude (measured per-step maxima: 0.036 ... 0.24, median 0.065).
constexpr double kBoundFactor = 10;
// The last iteration above round-off must cut the residual by at least this factor. Newton with
// a consistent tangent contracts by C r_k, which is tiny at the end of a step (measured: 3e-5 ...
// 6e-4); a tangent with a relative error delta converges linearly with contraction ~delta, so
// this bound rejects tangents more than 1 % off.
constexpr double kMaxFinalContraction = 1e-2;

// r_{k+1} / r_k^2 for k >= 2 while r_{k+1} is above the round-off floor. The first iteration is
// left out: its right-hand side carries the prescribed increment (K_fp du_p), a different
// function from the residual the later iterations reduce.
std::vector<double> quadraticRatios(const std::vector<double>& residuals) {
  std::vector<double> ratios;
  const double floor = kRoundoffFloor * residuals.front();
  for (std::size_t k = 1; k + 1 < residuals.size(); ++k) {
    if (residuals[k + 1] < floor) break;
    ratios.push_back(residuals[k + 1] / (residuals[k] * residuals[k]));
  }
  return ratios;
}

struct RateVerdict {
  double observedConstant = 0;        // median over the steps of the largest ratio of each step
  bool bounded = true;                // every ratio <= kBoundFactor * observedConstant
  bool finalContractionSmall = true;  // each step's last r_{k+1} / r_k <= kMaxFinalContraction
  bool enoughData = true;             // at least two ratios per step
};

RateVerdict checkQuadraticRate(const std::vector<std::vector<double>>& residualsPerStep) {
  RateVerdict verdict;
  std::vector<std::vector<double>> ratiosPerStep;
  std::vector<double> stepMaxima;
  for (const std::vector<double>& residuals : residualsPerStep) {
    ratiosPerStep.push_back(quadraticRatios(residuals));
    const std::vector<double>& ratios = ratiosPerStep.back();
    if (ratios.size() < 2) {
      verdict.enoughData = false;
      return verdict;
    }
    stepMaxima.push_back(*std::max_element(ratios.begin(), ratios.end()));
    // Ratio j is residuals[j + 2] / residuals[j + 1]^2, so residuals[n + 1] (n ratios) is the
    // last residual above round-off.
    const double lastContraction = residuals[ratios.size() + 1] / residuals[ratios.size()];
    verdict.finalContractionSmall =
        verdict.finalContractionSmall && lastContraction <= kMaxFinalContraction;
  }
  std::sort(stepMaxima.begin(), stepMaxima.end());
  const std::size_t middle = stepMaxima.size() / 2;
  verdict.observedConstant = stepMaxima.size() % 2
                                 ? stepMaxima[middle]
                                 : 0.5 * (stepMaxima[middle - 1] + stepMaxima[middle]);
  for (const std::vector<double>& ratios : ratiosPerStep) {
    for (double ratio : ratios) {
      verdict.bounded = verdict.bounded && ratio <= kBoundFactor * verdict.observedConstant;
    }
  }
  return verdict;
}

std::vector<std::vector<double>> residualHistories(const cc::test::DeckRun& run) {
  std::vector<std::vector<double>> histories;
  for (const cc::test::RecordedStep& step : run.steps) {
    std::vector<double> residuals;
    for (const cc::IterationRecord& row : run.iterationsOf(step.step)) {
      residuals.push_back(row.residualNorm);
    }
    histories.push_back(residuals);
  }
  return histories;
}

const cc::test::DeckRun& bendingRun() {
  static const cc::test::DeckRun run =
      cc::test::runDeckFile(cc::test::coreDeckPath("neohooke_bending.deck"));
  return run;
}

TEST(NewtonRate, QuadraticOnLargeDeformationNeoHookeBending) {
  const cc::test::DeckRun& run = bendingRun();
  ASSERT_EQ(run.summary.outcome, cc::RunSummary::Outcome::Completed) << run.summary.message;
  ASSERT_EQ(run.steps.size(), 4u);
  ASSERT_TRUE(run.cutbacks.empty());  // one attempt per step: each history is one Newton solve
  const std::vector<std::vector<double>> histories = residualHistories(run);
  for (std::size_t s = 0; s < histories.size(); ++s) {
    std::cout << "step " << s + 1 << " r_{k+1}/r_k^2:";
    for (double ratio : quadraticRatios(histories[s])) std::cout << " " << ratio;
    std::cout << "\n";
  }
  const RateVerdict verdict = checkQuadraticRate(histories);
  std::cout << "observed Newton constant (median of the step maxima) " << verdict.observedConstant
            << "\n";
  ASSERT_TRUE(verdict.enoughData);
  EXPECT_TRUE(verdict.bounded);
  EXPECT_TRUE(verdict.finalContractionSmall);
}

// The same histories with every iteration after the third replaced by a linear contraction
// (rate kLinearRate) down to the round-off floor, as an inconsistent tangent would give: the
// check must reject them.
TEST(NewtonRate, CheckRejectsLinearConvergence) {
  constexpr double kLinearRate = 0.05;
  constexpr std::size_t kKeptIterations = 3;
  std::vector<std::vector<double>> linear = residualHistories(bendingRun());
  ASSERT_FALSE(linear.empty());
  for (std::vector<double>& residuals : linear) {
    ASSERT_GE(residuals.size(), kKeptIterations);
    residuals.resize(kKeptIterations);
    while (residuals.back() > kRoundoffFloor * residuals.front()) {
      residuals.push_back(kLinearRate * residuals.back());
    }
  }
  const RateVerdict verdict = checkQuadraticRate(linear);
  ASSERT_TRUE(verdict.enoughData);
  EXPECT_FALSE(verdict.finalContractionSmall);
}

}  // namespace
