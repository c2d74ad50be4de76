// Step control (issue 7): a step that inverts elements is retried with the line search (and cut
// back if that fails too) and the run finishes at the right equilibrium; an inversion no step
// size avoids stops the run with the element named; a cut-back leaves the contact history
// exactly as it was (the cut path equals the same sub-steps taken plainly); and every cut-back
// is logged and counted in the results file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "output/results_reader.hpp"
#include "stress_support.hpp"

namespace cc::test {
namespace {

// A Newton iterate that folds elements is an overshoot of the full Newton step more often than a
// step too large (issue 14: the faceted NTS ironing die inverted a slab element at every step
// size below 1e-10 and the run stopped at t = 0.495; with the line search it completes without
// a cut-back). So the step is first retried with the line search, which backs off from inverted
// configurations, and cut back only if that fails as well (the cut-backs: the next test).
TEST(InvertedElement,
     OneDeepPunchStepIsRetriedWithLineSearchAndEndsAtTheEquilibriumOfSixteenSteps) {
  const DeckRun oneStep = runStressDeck("inverted_element_cutback");
  ASSERT_EQ(oneStep.summary.outcome, RunSummary::Outcome::Completed) << oneStep.summary.message;
  int inversions = 0;
  for (const CutbackRecord& cutback : oneStep.cutbacks) {
    if (cutback.reason.find("det J") != std::string::npos &&
        cutback.reason.find("gmsh element") != std::string::npos) {
      ++inversions;
    }
  }
  EXPECT_GE(inversions, 1) << "no retry was caused by an inverted element";
  EXPECT_GE(oneStep.summary.lineSearchRetries, 1);
  EXPECT_EQ(oneStep.summary.totalCutbacks, 0);
  EXPECT_EQ(oneStep.summary.stepsConverged, 1);
  std::cout << "punch in one step: " << oneStep.summary.stepsConverged << " steps, "
            << oneStep.summary.lineSearchRetries << " line-search retries, "
            << oneStep.summary.totalCutbacks << " cut-backs (" << inversions
            << " for inverted elements)\n";
  const std::string deck = readText(stressDeck("inverted_element_cutback"));
  const DeckRun sixteen = runStressText(replaceOnce(deck, "steps 1 dt=1 ", "steps 16 dt=0.0625 "),
                                        "inverted_element_cutback");
  ASSERT_EQ(sixteen.summary.outcome, RunSummary::Outcome::Completed) << sixteen.summary.message;
  // Hyperelastic and frictionless: the end state does not depend on the path (measured 2e-9
  // relative between the two, the Newton tolerance of a 500-unit force).
  const Eigen::Vector3d force = oneStep.steps.back().pair("punch").totalForce;
  const Eigen::Vector3d reference = sixteen.steps.back().pair("punch").totalForce;
  EXPECT_GT(reference.y(), 0);
  EXPECT_LT((force - reference).norm(), 1e-7 * reference.norm());
}

// A run whose attempts are damped where they stand, against the same steps with the line search
// from every first iteration: both complete `steps` steps, the damped run without a retry, a
// failed attempt or a cut-back, and every step's die force is the searched run's to 1e-8. Two
// Newton paths to each step's equilibrium; friction makes the end state depend on the path
// within the tolerance (measured: at most 2.4e-13 of the force; bound: 1e-8, the relative
// residual at which the energy criterion of 1e-16 is met here).
void expectDampedRunMatchesSearched(const DeckRun& damped, const DeckRun& searched,
                                    std::size_t steps) {
  for (const DeckRun* run : {&damped, &searched}) {
    ASSERT_EQ(run->summary.outcome, RunSummary::Outcome::Completed) << run->summary.message;
    ASSERT_EQ(run->steps.size(), steps);
  }
  EXPECT_EQ(damped.summary.lineSearchRetries, 0);
  EXPECT_EQ(damped.summary.discardedIterations, 0);
  EXPECT_EQ(damped.summary.totalCutbacks, 0);
  for (std::size_t k = 0; k < steps; ++k) {
    const Eigen::Vector3d force = damped.steps[k].pair("die").totalForce;
    const Eigen::Vector3d reference = searched.steps[k].pair("die").totalForce;
    EXPECT_GT(reference.norm(), 0.1);
    EXPECT_LT((force - reference).norm(), 1e-8 * reference.norm()) << "step " << k + 1;
  }
}

// A plain attempt whose residual stops improving near convergence takes the rest of its updates
// through the line search (newton_stall.hpp, stagnatesNearConvergence) instead of running to
// the iteration limit and being retried from the step's start. The ironing press at mu = 0.6
// with NTS (the committed deck's first four steps, FEAP's predictor): step 4 came down to
// 2.6e-7 of its reference at iteration 3 and then alternated between 2.4e-7 and 2.9e-7, no
// point changing state, for all 30 iterations; its retry converged in 7 (19 + 30 iterations in
// all). Damped from iteration 9, its first attempt converges at iteration 13 (25 in all, none
// discarded), at the equilibrium the same steps reach with the line search from their first
// iteration (19 iterations, each with a residual assembly per trial step).
TEST(StepControl, AnAttemptThatStagnatesNearConvergenceIsDampedWithoutARestart) {
  const std::string name = "ironing/ironing_nts_mu06_wide";
  const std::string deck = readText(stressDeck(name));
  const DeckRun press = runStressText(replaceOnce(deck, "steps 100 ", "steps 4 "), name);
  const DeckRun searched = runStressText(
      replaceOnce(deck, "  steps 100 ", "  newton line_search=yes\n  steps 4 "), name);
  ASSERT_NO_FATAL_FAILURE(expectDampedRunMatchesSearched(press, searched, 4));
  // Plain updates first, then only line-search ones once the stagnation showed.
  const std::vector<IterationRecord> step4 = press.iterationsOf(4);
  ASSERT_FALSE(step4.empty());
  const auto firstDamped = std::find_if(step4.begin(), step4.end(), [](const IterationRecord& row) {
    return row.lineSearchFraction > 0;
  });
  ASSERT_NE(firstDamped, step4.end()) << "step 4 was not damped";
  EXPECT_GE(firstDamped->iteration, 6);  // the stagnation test needs four iterations above a best
  EXPECT_LT(firstDamped->relativeResidual, 1e-3);
  for (auto row = firstDamped; row != step4.end(); ++row) EXPECT_GT(row->lineSearchFraction, 0);
  const Eigen::Vector3d force = press.steps.back().pair("die").totalForce;
  const Eigen::Vector3d reference = searched.steps.back().pair("die").totalForce;
  std::cout << "press step 4: " << step4.size() << " iterations, damped from iteration "
            << firstDamped->iteration << "; die force " << force.transpose() << " against "
            << reference.transpose() << " with the line search throughout\n";
}

TEST(StepControl, AnActiveSetCycleNearConvergenceIsDampedWithoutARestart) {
  // The smoothed ironing die's first drag step (t = 0.21) with the extrapolating predictor:
  // its first update leaves 2e-6 of the step's residual, and the stick/slip states of 16-30
  // points then return at iteration 5 to an earlier iteration's. Such a cycle used to end the
  // attempt and the step was retried with the line search from its start (4 + 7 iterations);
  // near convergence it is now damped where it stands (9 iterations in all).
  const std::string name = "ironing/ironing_sts_mu03_wide_smooth";
  const std::string deck = readText(stressDeck(name));
  const DeckRun drag = runStressText(
      replaceOnce(deck, "  steps 100 ", "  newton predictor=extrapolate\n  steps 21 "), name);
  const DeckRun searched =
      runStressText(replaceOnce(deck, "  steps 100 ",
                                "  newton predictor=extrapolate line_search=yes\n  steps 21 "),
                    name);
  ASSERT_NO_FATAL_FAILURE(expectDampedRunMatchesSearched(drag, searched, 21));
  const std::vector<IterationRecord> step21 = drag.iterationsOf(21);
  const auto firstDamped =
      std::find_if(step21.begin(), step21.end(),
                   [](const IterationRecord& row) { return row.lineSearchFraction > 0; });
  ASSERT_NE(firstDamped, step21.end()) << "step 21 was not damped";
  EXPECT_LT(firstDamped->relativeResidual, 1e-3);
  for (auto row = step21.begin(); row != firstDamped; ++row) EXPECT_GT(row->contact.state, 0);
  std::cout << "first drag step: " << step21.size() << " iterations, damped from iteration "
            << firstDamped->iteration << "\n";
}

TEST(InvertedElement, AnInversionNoStepAvoidsStopsTheRunNamingTheElement) {
  const std::string directory = scratchDirectory("inverted_persistent");
  const CommandResult result = runCovcontact(
      "run -q --threads 1 '" + stressDeck("inverted_element_persistent") + "' -o run.h5",
      directory);
  EXPECT_EQ(result.exitCode, kExitDiverged) << result.error;
  EXPECT_NE(result.error.find("failed after 8 cut-backs"), std::string::npos) << result.error;
  EXPECT_NE(result.error.find("gmsh element"), std::string::npos) << result.error;
  EXPECT_NE(result.error.find("det J"), std::string::npos) << result.error;
  const ResultsReader reader(directory + "/run.h5");
  ASSERT_EQ(reader.steps().size(), 1u);  // the converged first step is kept
  EXPECT_EQ(reader.stringAttribute("/summary", "outcome"), "diverged");
}

// The converged steps of `cut` replayed as plain steps: one phase per step, same settings.
std::string replayDeck(const std::string& deck, const DeckRun& cut) {
  std::ostringstream phases;
  phases.precision(17);
  double previous = 0;
  for (const RecordedStep& step : cut.steps) {
    phases << "  steps 1 dt=" << step.time - previous << (step.time > 1 ? " maxit=8" : "") << "\n";
    previous = step.time;
  }
  return replaceOnce(deck, "  steps 1 dt=1\n  steps 1 dt=1 maxit=8\n", phases.str());
}

TEST(CutBack, ACutStepEndsInTheContactStateOfTheSameSubStepsTakenPlainly) {
  const std::string deck = readText(stressDeck("cutback_equivalence"));
  const DeckRun cut = runStressDeck("cutback_equivalence");
  ASSERT_EQ(cut.summary.outcome, RunSummary::Outcome::Completed) << cut.summary.message;
  ASSERT_GE(cut.summary.totalCutbacks, 1);
  const DeckRun plain = runStressText(replayDeck(deck, cut), "cutback_equivalence");
  ASSERT_EQ(plain.summary.outcome, RunSummary::Outcome::Completed) << plain.summary.message;
  EXPECT_EQ(plain.summary.totalCutbacks, 0);
  ASSERT_EQ(plain.steps.size(), cut.steps.size());
  std::cout << "cut path: " << cut.summary.totalCutbacks << " cut-backs, steps at t =";
  for (const RecordedStep& step : cut.steps) std::cout << " " << step.time;
  std::cout << "\n";
  for (std::size_t k = 0; k < cut.steps.size(); ++k) {
    SCOPED_TRACE("step " + std::to_string(k + 1));
    EXPECT_EQ(plain.steps[k].time, cut.steps[k].time);
    EXPECT_EQ(plain.steps[k].iterations, cut.steps[k].iterations);
    const ContactPairRecord& a = cut.steps[k].pair("interface");
    const ContactPairRecord& b = plain.steps[k].pair("interface");
    for (Eigen::Index i = 0; i < a.state.size(); ++i) EXPECT_EQ(a.state[i], b.state[i]);
    // Failed attempts leave no trace at all: the same arithmetic, so bitwise the same numbers
    // (a leaked trial state would differ by the step's slip increment, ~1e-3 relative).
    EXPECT_EQ(a.tangentialTraction, b.tangentialTraction);
    EXPECT_EQ(a.normalTraction, b.normalTraction);
    EXPECT_EQ(a.accumulatedSlip, b.accumulatedSlip);
    EXPECT_EQ(a.totalForce, b.totalForce);
    EXPECT_EQ(cut.steps[k].displacement, plain.steps[k].displacement);
  }
}

TEST(CutBack, EveryCutBackIsLoggedAndCountedInTheResultsFile) {
  const std::string directory = scratchDirectory("cutback_log");
  const CommandResult result = runCovcontact(
      "run -q --threads 1 '" + stressDeck("cutback_equivalence") + "' -o run.h5", directory);
  ASSERT_EQ(result.exitCode, kExitOk) << result.error;
  const ResultsReader reader(directory + "/run.h5");
  const int summaryCutbacks = static_cast<int>(reader.numberAttribute("/summary", "cutbacks"));
  int perStep = 0;
  for (const StepHeader& step : reader.steps()) perStep += step.cutbacks;
  int logged = 0, retries = 0;
  for (const CutbackRecord& row : reader.cutbacks()) {
    EXPECT_FALSE(row.reason.empty());
    EXPECT_GT(row.newDt, 0);
    (row.reason.rfind("retrying the step with line search", 0) == 0 ? retries : logged) += 1;
  }
  EXPECT_GE(summaryCutbacks, 1);
  EXPECT_EQ(logged, summaryCutbacks);
  EXPECT_EQ(perStep, summaryCutbacks);
  // The convergence table holds the failed attempts too: attempt numbers up to the cut-backs
  // (and line-search retries) of a step.
  int highestAttempt = 0;
  for (const IterationRecord& row : reader.convergence())
    highestAttempt = std::max(highestAttempt, row.attempt);
  EXPECT_EQ(highestAttempt, summaryCutbacks + retries);
  EXPECT_NE(result.output.find("cut-back"), std::string::npos);  // and reported as they happen
}

}  // namespace
}  // namespace cc::test
