// Step control (issue 7): a step that inverts elements is retried with the line search (and cut
// back if that fails too) and the run finishes at the right equilibrium; an inversion no step
// size avoids stops the run with the element named; a cut-back leaves the contact history
// exactly as it was (the cut path equals the same sub-steps taken plainly); and every cut-back
// is logged and counted in the results file.
#include <gtest/gtest.h>

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
