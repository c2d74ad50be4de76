// Convergence tests that must not lie (issue 15): a step that no load drives converges at once
// instead of "diverging" on its own round-off; the criteria are scale free (a modulus of 1e-300
// takes the same iterations to the same displacements as 200, where the underflowing residual
// norm used to accept the first iterate); and cut-backs stop once a step no longer moves time.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>

#include "stress_support.hpp"

namespace cc::test {
namespace {

// A unit cube of 2 x 2 x 2 Hex8 on its bottom face; MODEL and DRIVE are replaced.
const std::string kCubeDeck = R"(mesh "meshes/cube.geo"
material solid MODEL nu=0.3
elements cube hex8 material=solid
fix bottom all
DRIVE
SOLVE)";

std::string cubeDeck(const std::string& model, const std::string& drive, const std::string& solve) {
  std::string deck = replaceOnce(kCubeDeck, "MODEL", model);
  deck = replaceOnce(deck, "DRIVE", drive);
  return replaceOnce(deck, "SOLVE", solve);
}

DeckRun runCube(const std::string& deck) {
  // The virtual path anchors "meshes/cube.geo" in tests/decks.
  return runDeckText(deck, std::string(COVCONTACT_SOURCE_DIR) + "/tests/decks/cube.deck");
}

double relativeDifference(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) {
  return (a - b).norm() / b.norm();
}

TEST(ConvergenceTruth, AStepWithoutLoadConvergesAndTheRunEndsWhereTheLoadAloneLeadsIt) {
  // The load starts after t = 1: step 1 has nothing to do. Its residual is the round-off of
  // F = I computed from x = X (1e-14 here), which a test relative to the forces never reached.
  const DeckRun late = runCube(cubeDeck("svk E=200", R"(load top fz "t > 1 ? -(t - 1) : 0" total)",
                                        "solve\n  steps 3 dt=1\nend\n"));
  ASSERT_EQ(late.summary.outcome, RunSummary::Outcome::Completed) << late.summary.message;
  EXPECT_EQ(late.summary.totalCutbacks, 0);
  EXPECT_EQ(late.steps.front().iterations, 1);
  // Hyperelastic: the end state depends only on the final load (-2), reached here directly.
  const DeckRun direct =
      runCube(cubeDeck("svk E=200", R"(load top fz "-t" total)", "solve\n  steps 2 dt=1\nend\n"));
  ASSERT_EQ(direct.summary.outcome, RunSummary::Outcome::Completed) << direct.summary.message;
  EXPECT_LT(relativeDifference(late.steps.back().displacement, direct.steps.back().displacement),
            1e-8);
}

TEST(ConvergenceTruth, ATinyModulusTakesTheSameIterationsToTheSameDisplacements) {
  // A prescribed stretch: displacements do not depend on E, forces scale with it. With
  // E = 1e-300 the squared residual entries underflowed, ||R|| was 0 and the first iterate was
  // accepted (0.1 % off, exit 0).
  const std::string drive = R"(prescribe top uz "0.1*t")";
  const std::string solve = "solve\n  steps 2 dt=1\nend\n";
  const DeckRun ordinary = runCube(cubeDeck("neohooke E=200", drive, solve));
  const DeckRun tiny = runCube(cubeDeck("neohooke E=1e-300", drive, solve));
  ASSERT_EQ(ordinary.summary.outcome, RunSummary::Outcome::Completed);
  ASSERT_EQ(tiny.summary.outcome, RunSummary::Outcome::Completed) << tiny.summary.message;
  ASSERT_EQ(tiny.steps.size(), ordinary.steps.size());
  for (std::size_t k = 0; k < tiny.steps.size(); ++k) {
    EXPECT_EQ(tiny.steps[k].iterations, ordinary.steps[k].iterations) << "step " << k + 1;
    EXPECT_GT(tiny.steps[k].iterations, 1) << "step " << k + 1;
    EXPECT_LT(relativeDifference(tiny.steps[k].displacement, ordinary.steps[k].displacement), 1e-8)
        << "step " << k + 1;
    const Eigen::Vector3d scaled = tiny.steps[k].setReaction("top") * (200 / 1e-300);
    const Eigen::Vector3d reference = ordinary.steps[k].setReaction("top");
    EXPECT_LT((scaled - reference).norm(), 1e-8 * reference.norm()) << "step " << k + 1;
  }
}

TEST(ConvergenceTruth, CutBacksStopWhenTheStepNoLongerMovesTime) {
  // One Newton iteration never converges (the energy test compares the first solve with
  // itself), whatever the step size; with 5000 cut-backs allowed the step size went to 0.
  const DeckRun run =
      runCube(cubeDeck("svk E=200", R"(prescribe top uz "0.1*t")",
                       "solve\n  newton maxit=1\n  steps 1 dt=1 cutback_max=5000\nend\n"));
  EXPECT_EQ(run.summary.outcome, RunSummary::Outcome::Diverged);
  EXPECT_NE(run.summary.message.find("would no longer move time"), std::string::npos)
      << run.summary.message;
  // Halving from 1 to the smallest step of 1e-8 dt: 26 cut-backs (2^-26 = 1.5e-8).
  EXPECT_EQ(run.summary.totalCutbacks, 26) << run.summary.message;
}

TEST(ConvergenceTruth, RetriesWithLineSearchAndTheirIterationsAreCounted) {
  // Example 6.1 with friction: plain Newton fails twice in 30 iterations and is retried with
  // line search. Those iterations were in no summary ("148 Newton iterations, 0 cut-backs").
  const DeckRun run = runStressDeck("restart_6_1");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  int retries = 0;
  for (const CutbackRecord& record : run.cutbacks)
    retries += record.reason.rfind("retrying the step with line search", 0) == 0;
  // The iterations of attempts that did not converge: every logged row of an attempt other than
  // the last one of its step.
  std::map<int, int> lastAttempt;
  for (const IterationRecord& row : run.iterations)
    lastAttempt[row.step] = std::max(lastAttempt[row.step], row.attempt);
  int discarded = 0, kept = 0;
  for (const IterationRecord& row : run.iterations)
    (row.attempt < lastAttempt[row.step] ? discarded : kept) += 1;
  EXPECT_GT(retries, 0);
  EXPECT_EQ(run.summary.lineSearchRetries, retries);
  EXPECT_EQ(run.summary.discardedIterations, discarded);
  EXPECT_EQ(run.summary.totalIterations, kept);
}

}  // namespace
}  // namespace cc::test
