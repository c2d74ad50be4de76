// Extreme friction cases on example 6.1 (issue 7): the penalty sweep from 1e-1 E/h to 1e5 E/h,
// a sliding step of 10 u_cr (eq. (110)), mu = 0, mu = 1, and two pairs with different mu in one
// model. Each asserts the physical outcome: the Coulomb limit |T| = mu |N| at every sliding
// point and the force ratio mu of the whole interface, the convergence of the normal force with
// the penalty, path independence in full sliding, no tangential force without friction.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "stress_support.hpp"

namespace cc::test {
namespace {

constexpr double kMu = 0.3;
// Every sliding point is on the Coulomb cone up to the return mapping's round-off.
constexpr double kConeTolerance = 1e-9;
// The interface's force ratio |F_x / F_y| differs from the local |T| / |N| = mu only by the
// tilt of the deformed block bottom (normals off vertical by ~1e-4 here, measured from the
// tangential tractions' y components): allow 1e-3.
constexpr double kTiltTolerance = 1e-3;

struct SweepResult {
  double epsilonOverStiffness = 0;
  RunSummary summary;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  double maxPenetration = 0;
};

// The last step of a run of example 6.1: every active point slides, on the cone, and the
// interface transmits mu times its normal force.
void expectFullSliding(const RecordedStep& step, const std::string& pair, double mu) {
  const ContactPairRecord& record = step.pair(pair);
  const ContactSums sums = contactSums(record, mu);
  EXPECT_GT(sums.active(), 0);
  EXPECT_EQ(sums.stick, 0) << "points still sticking at t = " << step.time;
  EXPECT_LT(sums.worstConeError, kConeTolerance);
  EXPECT_NEAR(sums.tangential / sums.normal, mu, kConeTolerance * mu);
  EXPECT_NEAR(std::abs(record.totalForce.x() / record.totalForce.y()), mu, kTiltTolerance);
}

TEST(PenaltySweep, EveryPenaltyFrom1eMinus1To1e5EOverHFinishesAtTheSlidingRatio) {
  // E / h = 2.1e4 / 2 on the coarse mesh of penalty_sweep_6_1.deck (h = 20 / 10).
  const double stiffness = 2.1e4 / 2;
  const std::string deck = readText(stressDeck("penalty_sweep_6_1"));
  std::vector<SweepResult> results;
  for (int decade = -1; decade <= 5; ++decade) {
    SweepResult result;
    result.epsilonOverStiffness = std::pow(10.0, decade);
    const double epsilon = stiffness * result.epsilonOverStiffness;
    const std::string text =
        replaceOnce(deck, "eps_n=1.05e9 eps_t=1.05e9",
                    "eps_n=" + std::to_string(epsilon) + " eps_t=" + std::to_string(epsilon));
    const DeckRun run = runStressText(text, "penalty_sweep_6_1");
    result.summary = run.summary;
    ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed)
        << "eps = 1e" << decade << " E/h: " << run.summary.message;
    ASSERT_DOUBLE_EQ(run.steps.back().time, 11.0);
    SCOPED_TRACE("eps = 1e" + std::to_string(decade) + " E/h");
    expectFullSliding(run.steps.back(), "interface", kMu);
    const ContactPairRecord& pair = run.steps.back().pair("interface");
    result.force = pair.totalForce;
    for (Eigen::Index i = 0; i < pair.gap.size(); ++i) {
      if (pair.state[i] != 0) result.maxPenetration = std::max(result.maxPenetration, -pair.gap[i]);
    }
    std::cout << "eps = 1e" << decade << " E/h: " << run.summary.stepsConverged << " steps, "
              << run.summary.totalIterations << " iterations, " << run.summary.totalCutbacks
              << " cut-backs, F = " << pair.totalForce.transpose() << ", max penetration "
              << result.maxPenetration << "\n";
    results.push_back(result);
  }
  // The penalty solution approaches the impenetrable one as O(1/eps): the normal force grows
  // with eps, and its change shrinks by about 10 per decade once the contact is stiffer than
  // the block (eps > 10 E/h); at least 5 is asserted.
  for (std::size_t k = 1; k < results.size(); ++k) {
    EXPECT_GT(std::abs(results[k].force.y()), std::abs(results[k - 1].force.y()));
    EXPECT_LT(results[k].maxPenetration, results[k - 1].maxPenetration);
  }
  for (std::size_t k = 3; k < results.size(); ++k) {
    const double change = std::abs(results[k].force.y() - results[k - 1].force.y());
    const double previous = std::abs(results[k - 1].force.y() - results[k - 2].force.y());
    EXPECT_LT(change, previous / 5) << "decade " << k - 1;
  }
}

TEST(LargeSlipStep, TenTimesTheCriticalSlipInOneStepEndsWhereSmallStepsEnd) {
  // Reference: the same drag of 0.06 in 24 steps of u_cr / 2.4 = 2.5e-3.
  const DeckRun oneStep = runStressDeck("large_slip_step");
  ASSERT_EQ(oneStep.summary.outcome, RunSummary::Outcome::Completed) << oneStep.summary.message;
  const std::string deck = readText(stressDeck("large_slip_step"));
  const std::string slide = "  steps 1 dt=1\nend";
  const DeckRun smallSteps = runStressText(
      replaceOnce(deck, slide, "  steps 24 dt=0.041666666666666664\nend"), "large_slip_step");
  ASSERT_EQ(smallSteps.summary.outcome, RunSummary::Outcome::Completed);
  ASSERT_DOUBLE_EQ(smallSteps.steps.back().time, 2.0);
  std::cout << "one step of 10 u_cr: " << oneStep.summary.totalIterations << " iterations, "
            << oneStep.summary.totalCutbacks << " cut-backs\n";
  expectFullSliding(oneStep.steps.back(), "interface", kMu);
  // In full sliding the state no longer depends on the path: forces and displacements agree to
  // the Newton tolerance (measured 1e-12 relative).
  const Eigen::Vector3d big = oneStep.steps.back().pair("interface").totalForce;
  const Eigen::Vector3d small = smallSteps.steps.back().pair("interface").totalForce;
  EXPECT_LT((big - small).norm(), 1e-9 * small.norm());
  const Eigen::Matrix3Xd& u1 = oneStep.steps.back().displacement;
  const Eigen::Matrix3Xd& u24 = smallSteps.steps.back().displacement;
  EXPECT_LT((u1 - u24).cwiseAbs().maxCoeff(), 1e-9 * u24.cwiseAbs().maxCoeff());
}

TEST(Friction, WithoutFrictionTheBlockSlidesFreelyWithItsTop) {
  const DeckRun run = runStressDeck("frictionless_slide");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  const RecordedStep& last = run.steps.back();
  const ContactPairRecord& pair = last.pair("interface");
  const ContactSums sums = contactSums(pair, 0.0);
  EXPECT_GT(sums.active(), 0);
  EXPECT_EQ(sums.tangential, 0.0);  // mu = 0 computes no tangential traction at all
  // The horizontal force is only the normal forces' tilt (strain ~1e-3).
  EXPECT_LT(std::abs(pair.totalForce.x()), 1e-4 * std::abs(pair.totalForce.y()));
  // The block follows its top: its bottom moves by the drag 0.025 on average (the Poisson
  // expansion of the press is symmetric about the middle).
  const NodeSet& bottom = run.model->mesh().nodeSets.at("block_bottom");
  double mean = 0;
  for (int node : bottom.nodes) mean += last.displacement(0, node);
  mean /= static_cast<double>(bottom.nodes.size());
  EXPECT_NEAR(mean, 0.025, 1e-5);
}

TEST(Friction, MuOneSlidesAtForceRatioOne) {
  const DeckRun run = runStressDeck("high_friction_slide");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  expectFullSliding(run.steps.back(), "interface", 1.0);
}

TEST(Friction, TwoPairsInOneModelSlideEachAtItsOwnMu) {
  const DeckRun run = runStressDeck("two_pairs_friction");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  expectFullSliding(run.steps.back(), "left", 0.2);
  expectFullSliding(run.steps.back(), "right", 0.5);
}

}  // namespace
}  // namespace cc::test
