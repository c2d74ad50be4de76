// Extreme contact geometries and materials (issue 7): nu = 0.4999, a thin solid-shell strip
// (thickness 1/1000 of the span) on a rigid cylinder, points sliding off the master edge and
// back, slave points exactly on master vertices and edges, initially penetrating and initially
// separated bodies, contact lost and regained. Each is checked against a closed form, a
// symmetry, or a path-independent state of the same run.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>

#include "output/results_reader.hpp"
#include "stress_support.hpp"

namespace cc::test {
namespace {

// Force on node set `name` (its summed reaction) in the last step of a run.
Eigen::Vector3d reaction(const DeckRun& run, const std::string& name) {
  return run.steps.back().setReaction(name);
}

TEST(NearlyIncompressible, CubeOnRigidPlaneMatchesUniaxialStressClosedForm) {
  const DeckRun run = runStressDeck("nearly_incompressible_press");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  const double youngs = 1e3, poisson = 0.4999, penalty = 1e7;
  for (const RecordedStep& step : run.steps) {
    // Homogeneous uniaxial stress: lambda_z = 1 - u_top - g, S_zz = E E_zz, lateral Green strain
    // -nu E_zz, current contact area (1 + 2 E_xx) (the STAS weights); -eps_N g (1 + 2 E_xx) =
    // -lambda_z E E_zz. Solved by bisection for g.
    const double top = 1e-3 * step.time;
    auto residual = [&](double gap) {
      const double stretch = 1 - top - gap;
      const double strain = (stretch * stretch - 1) / 2;
      return -penalty * gap * (1 - 2 * poisson * strain) + stretch * youngs * strain;
    };
    double low = -top, high = 0;
    for (int i = 0; i < 200; ++i)
      ((residual(0.5 * (low + high)) > 0) ? low : high) = 0.5 * (low + high);
    const double gap = 0.5 * (low + high), stretch = 1 - top - gap;
    const double force = -stretch * youngs * (stretch * stretch - 1) / 2;
    // Trilinear elements reproduce the homogeneous state on the distorted mesh exactly: the
    // difference is the Newton tolerance (measured 3e-10 relative).
    EXPECT_NEAR(-step.setReaction("zmax").z(), force, 1e-8 * force) << "t = " << step.time;
    const ContactPairRecord& pair = step.pair("floor");
    EXPECT_NEAR(-pair.totalForce.z(), force, 1e-8 * force);  // on the rigid plane: downwards
    EXPECT_NEAR(pair.gap.minCoeff(), gap, 1e-8 * std::abs(gap));
    EXPECT_NEAR(pair.gap.maxCoeff(), gap, 1e-8 * std::abs(gap));
  }
}

TEST(ThinShell, StripOnRigidCylinderFollowsTheBeamSolutionBeforeAndAfterWrapping) {
  const DeckRun run = runStressDeck("thin_shell_on_cylinder");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  const double youngs = 2.1e11, poisson = 0.3, width = 0.05, thickness = 1e-3;
  const double halfSpan = 0.5, radius = 5;
  constexpr double kPenalty = 1e9, kElement = 0.5 / 50;
  const double bending = youngs * width * std::pow(thickness, 3) / (12 * (1 - poisson * poisson));
  int wrapped = 0;
  for (const RecordedStep& step : run.steps) {
    const double rise = step.time;  // the cylinder's uz(t) = t
    double force = 0, wrapEnd = 0;
    if (radius * rise < halfSpan * halfSpan / 3) {
      force = 3 * bending * rise / std::pow(halfSpan, 3);  // cantilever from x = 0
    } else {
      const double freeLength = std::sqrt(3 * halfSpan * halfSpan - 6 * radius * rise);
      force = bending / (radius * freeLength);
      wrapEnd = halfSpan - freeLength;
      ++wrapped;
    }
    // Beam theory neglects the rotations (slope at the end <= 0.06 here, relative effect of its
    // square, 4e-3) and the penalty's compliance; measured up to 2.9e-3.
    EXPECT_NEAR(step.setReaction("end_bottom").z(), -force, 5e-3 * force) << "rise " << rise;
    EXPECT_NEAR(step.pair("roller").totalForce.z(), -force, 5e-3 * force) << "rise " << rise;
    // Contact reaches no further than the wrap plus the length over which the penalty spreads
    // the concentrated force at its end (that of a beam on an elastic foundation eps_N b,
    // (4 EI / (eps_N b))^(1/4) = 0.017) and half an element (the Gauss points).
    const ContactPairRecord& pair = step.pair("roller");
    const double spread = std::pow(4 * bending / (kPenalty * width), 0.25);
    double reach = 0;
    for (Eigen::Index i = 0; i < pair.state.size(); ++i) {
      if (pair.state[i] != 0) reach = std::max(reach, pair.position(0, i));
    }
    EXPECT_LT(reach, wrapEnd + spread + kElement / 2) << "rise " << rise;
    if (wrapEnd > 0.05) {
      EXPECT_GT(reach, wrapEnd) << "rise " << rise;
    }
  }
  EXPECT_GE(wrapped, 3);  // both regimes are checked
  // The deck's ten steps, none cut back (issue 7's outcome): Newton opens the points that the
  // rising cylinder closes at each step's first iterate a few at a time, its residual
  // alternating far above its best while its energy norm falls. Ended on the residual alone
  // (newton_stall.hpp), the run took 78 steps and 7 cut-backs (fiftieth to fifty-first sessions).
  EXPECT_EQ(run.steps.size(), 10u);
  EXPECT_TRUE(run.cutbacks.empty());
}

TEST(SlideOffEdge, PointsLeaveTheMasterAndComeBackToTheSameState) {
  const DeckRun run = runStressDeck("slide_off_edge");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  ASSERT_EQ(run.steps.size(), 13u);
  const ContactPairRecord& pressed = run.steps[0].pair("interface");
  const ContactPairRecord& dragged = run.steps[6].pair("interface");  // t = 7: drag 1.5
  const ContactPairRecord& back = run.steps[12].pair("interface");
  // At the largest drag the block (master) covers x in [1.5, 21.5]: slave points left of 1.5
  // have no master under them, points right of 20 came in. (Under the block, the pointwise
  // penalty on this non-matching interface lets every other Gauss point open: a discretization
  // effect of STS, not asserted here.)
  int leftBehind = 0, cameIn = 0;
  for (Eigen::Index i = 0; i < dragged.state.size(); ++i) {
    const bool active = dragged.state[i] != 0;
    if (pressed.state[i] != 0 && !active) {
      ++leftBehind;
      EXPECT_TRUE(std::isnan(dragged.gap[i]) || dragged.gap[i] > 0);
    }
    if (pressed.state[i] == 0 && active) {
      ++cameIn;
      EXPECT_GT(dragged.position(0, i), 20.0);
    }
  }
  EXPECT_NEAR(dragged.totalForce.y(), run.steps[6].setReaction("block_top").y(),
              1e-9 * dragged.totalForce.norm());
  EXPECT_GT(leftBehind, 0);
  EXPECT_GT(cameIn, 0);
  // Without friction the elastic state depends only on the load: back at drag 0 it is the
  // pressed state again (measured 1e-11 relative in force, 1e-14 in displacement).
  for (Eigen::Index i = 0; i < back.state.size(); ++i) EXPECT_EQ(back.state[i], pressed.state[i]);
  EXPECT_LT((back.totalForce - pressed.totalForce).norm(), 1e-9 * pressed.totalForce.norm());
  EXPECT_LT((run.steps[12].displacement - run.steps[0].displacement).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(SlaveOnMasterVertices, EveryNodeOnAVertexOrEdgeIsFoundWithTheSameTraction) {
  const DeckRun run = runStressDeck("slave_on_master_vertices");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  const ContactPairRecord& pair = run.steps.back().pair("vertices");
  // 11 x 3 block bottom nodes, all on master vertices or edges.
  ASSERT_EQ(pair.state.size(), 33);
  const StackSolution exact = compressedStack(2.1e4, 6.0, 10.0, 2.1e6, 7e-3);
  for (Eigen::Index i = 0; i < pair.state.size(); ++i) {
    EXPECT_NE(pair.state[i], 0) << "node at " << pair.position.col(i).transpose();
    EXPECT_NEAR(pair.gap[i], exact.gap, 1e-9 * std::abs(exact.gap));
  }
  EXPECT_NEAR(pair.weight.sum(), 10.0, 1e-12);  // the tributary areas tile the interface
  EXPECT_NEAR(-reaction(run, "block_top").y(), exact.force, 1e-9 * exact.force);
  EXPECT_NEAR(pair.totalForce.y(), exact.force, 1e-9 * exact.force);
}

TEST(SlaveOnMasterEdges, GaussPointsOnSharedAndBoundaryEdgesGiveAMirrorSymmetricState) {
  const DeckRun run = runStressDeck("slave_on_master_edges_sts");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  const ContactPairRecord& pair = run.steps.back().pair("edges");
  ASSERT_EQ(pair.state.size(), 11);
  // The configuration is mirror symmetric about x = 10; a point on a master edge may sit on
  // either segment, which the kink of the deformed surface there (angle ~1e-6) lets differ by
  // about 1e-7 of the traction (measured); 1e-5 is asserted.
  for (Eigen::Index i = 0; i < pair.state.size(); ++i) {
    EXPECT_NE(pair.state[i], 0) << "point at x = " << pair.position(0, i);
    Eigen::Index mirror = 0;
    double distance = 1e300;
    for (Eigen::Index j = 0; j < pair.state.size(); ++j) {
      const double d = std::abs(pair.position(0, j) - (20 - pair.position(0, i)));
      if (d < distance) distance = d, mirror = j;
    }
    EXPECT_LT(distance, 1e-6);
    EXPECT_NEAR(pair.normalTraction[i], pair.normalTraction[mirror],
                1e-5 * std::abs(pair.normalTraction[i]));
  }
  // The force on the base (slave) is the block's top reaction passed through it.
  EXPECT_NEAR(pair.totalForce.y(), reaction(run, "block_top").y(), 1e-9 * pair.totalForce.norm());
  EXPECT_LT(std::abs(pair.totalForce.x()), 1e-6 * pair.totalForce.norm());
}

// A penalty too soft for the mesh (ContactPair::penetrationWarning): the NTS stack of
// slave_on_master_vertices.deck shortened by 1.0 at eps_N = 2.1e3, a sixtieth of the automatic
// penalty 10 E/h = 1.26e5. The deepest penetration must be the closed form's gap (0.60), at the
// last step, measured against the block's elements (5/3 deep, E/h = 1.26e4: the softer side;
// the base's are 1 deep): 36 % of it, above the quarter that is reported. At the deck's
// eps_N = 2.1e6 it is 7e-6 of the depth and nothing is said.
std::string softStackDeck() {
  std::string deck = readText(stressDeck("slave_on_master_vertices"));
  deck = replaceOnce(deck, "\"-7e-3*t\"", "\"-1.0*t\"");
  deck = replaceOnce(deck, "eps_n=2.1e6", "eps_n=2.1e3");
  return replaceOnce(deck, "steps 1 dt=1", "steps 4 dt=0.25");
}

TEST(SoftPenalty, ThePenetrationAgainstTheElementDepthIsReportedAtTheEnd) {
  const DeckRun soft = runStressText(softStackDeck(), "slave_on_master_vertices");
  ASSERT_EQ(soft.summary.outcome, RunSummary::Outcome::Completed) << soft.summary.message;
  const contact::ContactPair& pair = *soft.model->contactPairs()[0];
  const StackSolution exact = compressedStack(2.1e4, 6.0, 10.0, 2.1e3, 1.0);
  EXPECT_NEAR(pair.deepestPenetration(), -exact.gap, 1e-9 * std::abs(exact.gap));
  EXPECT_EQ(pair.deepestPenetrationTime(), 1.0);
  EXPECT_NEAR(pair.config().layerDepth, 5.0 / 3.0, 1e-10);  // gmsh writes 1e-12 round-off
  const std::string warning = pair.penetrationWarning();
  EXPECT_NE(warning.find(fmt::format("the penetration reached {:.3g} at t = 1, {:.0f} % of the "
                                     "depth of the elements behind the softer surface (1.67)",
                                     -exact.gap, -100 * exact.gap / (5.0 / 3.0))),
            std::string::npos)
      << warning;
  EXPECT_NE(warning.find("automatic penalty for this mesh, 10 E/h: 1.26e+05"), std::string::npos)
      << warning;

  const DeckRun stiff = runStressDeck("slave_on_master_vertices");
  EXPECT_EQ(stiff.model->contactPairs()[0]->penetrationWarning(), "");
  EXPECT_GT(stiff.model->contactPairs()[0]->deepestPenetration(), 0.0);
}

// A deck text from softStackDeck() written as soft.deck into the scratch folder `name` (its mesh
// path made absolute), for runs of the command; returns the folder.
std::string writeSoftStackDeck(const std::string& name, const std::string& text) {
  const std::string directory = scratchDirectory(name);
  std::ofstream(directory + "/soft.deck") << replaceOnce(
      text, "\"../../meshes/", "\"" + std::string(COVCONTACT_SOURCE_DIR) + "/meshes/");
  return directory;
}

// The same line on the command line: printed at the end of the run and kept in the results
// file's /summary (attribute warnings), so that a script reading results can see it.
TEST(SoftPenalty, TheLineIsPrintedAndKeptInTheResultsFile) {
  const std::string directory = writeSoftStackDeck("soft_penalty", softStackDeck());
  const CommandResult run = runCovcontact("run -q --threads 1 soft.deck -o soft.h5", directory);
  ASSERT_EQ(run.exitCode, 0) << run.error;
  const std::size_t at = run.output.find("contact 'vertices': the penetration reached ");
  ASSERT_NE(at, std::string::npos) << run.output;
  const std::string line = run.output.substr(at, run.output.find('\n', at) + 1 - at);
  EXPECT_EQ(ResultsReader(directory + "/soft.h5").stringAttribute("/summary", "warnings"), line);
}

// The deepest penetration is restart data: the stack pressed to t = 1 and released to t = 1.75,
// continued from step 5 (t = 1.25, past the deepest state), must end with the uninterrupted run's
// line, which names t = 1. A watch that started again at the restart sees only t = 1.5 and 1.75
// (shortenings of 0.5 and 0.25, below the quarter of the depth) and says nothing (checked).
TEST(SoftPenalty, ARunContinuedPastTheDeepestStateReportsIt) {
  const std::string pressAndRelease =
      replaceOnce(replaceOnce(softStackDeck(), "\"-1.0*t\"", "\"-1.0*min(t,2-t)\""),
                  "steps 4 dt=0.25", "steps 7 dt=0.25");
  const std::string directory = writeSoftStackDeck("soft_penalty_restart", pressAndRelease);
  const CommandResult full = runCovcontact("run -q --threads 1 soft.deck -o full.h5", directory);
  ASSERT_EQ(full.exitCode, 0) << full.error;
  const CommandResult continued = runCovcontact(
      "run -q --threads 1 soft.deck --restart full.h5 --from-step 5 -o continued.h5", directory);
  ASSERT_EQ(continued.exitCode, 0) << continued.error;
  const std::string expected =
      ResultsReader(directory + "/full.h5").stringAttribute("/summary", "warnings");
  EXPECT_NE(expected.find(" at t = 1, "), std::string::npos) << expected;
  EXPECT_EQ(ResultsReader(directory + "/continued.h5").stringAttribute("/summary", "warnings"),
            expected);
}

TEST(InitialGap, PenetratingBodiesArePushedApartIntoTheClosedFormState) {
  const DeckRun run = runStressDeck("initially_penetrating");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  const StackSolution exact = compressedStack(2.1e4, 6.0, 10.0, 2.1e6, 0.01);
  EXPECT_NEAR(-reaction(run, "block_top").y(), exact.force, 1e-9 * exact.force);
  const ContactPairRecord& pair = run.steps.back().pair("interface");
  EXPECT_NEAR(pair.gap.minCoeff(), exact.gap, 1e-9 * std::abs(exact.gap));
  EXPECT_NEAR(pair.gap.maxCoeff(), exact.gap, 1e-9 * std::abs(exact.gap));
}

TEST(InitialGap, SeparatedBodiesCloseAndCarryOnlyTheRemainingShortening) {
  const DeckRun run = runStressDeck("initially_separated");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  // t = 0.5: the top moved 0.01, exactly the gap: at most touching, no force.
  EXPECT_LT(std::abs(run.steps[0].setReaction("block_top").y()), 1e-9);
  const StackSolution exact = compressedStack(2.1e4, 6.0, 10.0, 2.1e6, 0.01);
  EXPECT_NEAR(-reaction(run, "block_top").y(), exact.force, 1e-9 * exact.force);
  EXPECT_EQ(contactSums(run.steps.back().pair("interface"), 0).open, 0);
}

TEST(ContactLostAndRegained, LiftingClearsTheContactAndPressingAgainRepeatsTheFirstPress) {
  const DeckRun run = runStressDeck("contact_lost_regained");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << run.summary.message;
  ASSERT_EQ(run.steps.size(), 3u);
  const ContactPairRecord& lifted = run.steps[1].pair("interface");
  EXPECT_EQ(contactSums(lifted, 0.3).active(), 0);
  EXPECT_EQ(lifted.totalForce.norm(), 0.0);
  const ContactPairRecord& first = run.steps[0].pair("interface");
  const ContactPairRecord& again = run.steps[2].pair("interface");
  // Lifting resets the tangential history, so the second press starts as the first did: the
  // same states and forces (measured 1e-11 relative) and displacements.
  for (Eigen::Index i = 0; i < first.state.size(); ++i) EXPECT_EQ(again.state[i], first.state[i]);
  EXPECT_LT((again.totalForce - first.totalForce).norm(), 1e-9 * first.totalForce.norm());
  EXPECT_LT((again.tangentialTraction - first.tangentialTraction).cwiseAbs().maxCoeff(),
            1e-8 * first.normalTraction.cwiseAbs().maxCoeff());
  EXPECT_LT((run.steps[2].displacement - run.steps[0].displacement).cwiseAbs().maxCoeff(), 1e-11);
}

}  // namespace
}  // namespace cc::test
