// The verification decks of input/verification/contact against their analytic solutions (issue 6).
// Targets (on the deck's mesh, which runs in under a minute): Hertz peak pressure within 3%,
// contact radius within one element, P(delta) within 2%, Cattaneo-Mindlin stick radius within one
// element width, STS patch test on matching meshes uniform to 1e-3. Where the deck's mesh is too
// slow for CTest, a coarser mesh runs here and must meet the target's absolute tolerance (one
// element of the *deck's* mesh, not of the coarse one); where it cannot, the test asserts only
// what the coarse mesh meets and says so, and scripts/error_vs_time.py runs the deck's mesh
// (docs/verification/accuracy.md has both numbers).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "verification_runs.hpp"

namespace cc::test {
namespace {

const std::string kDecks = std::string(COVCONTACT_SOURCE_DIR) + "/input/verification/contact/";
constexpr double kZoneHalfSize = 1.5;  // c of meshes/indented_block.geo in every deck here

double elementSize(int m) {
  return kZoneHalfSize / m;
}

// eps_N (and eps_T) of the deck scaled to mesh level m at the deck's alpha = eps h / E.
DeckChanges meshLevel(int m, int deckLevel, std::map<std::string, std::string> extra = {}) {
  DeckChanges changes;
  changes.mesh = std::move(extra);
  changes.mesh["m"] = std::to_string(m);
  changes.penaltyScale = static_cast<double>(m) / deckLevel;
  return changes;
}

void expectCompleted(const VerifiedRun& verified) {
  ASSERT_EQ(verified.run.summary.outcome, RunSummary::Outcome::Completed)
      << verified.run.summary.message;
}

// Hertz sphere targets: P(delta) within 2%, contact radius within one element h, peak pressure
// within 3% (the largest point pressure; the centre point's pressure is held to the same 3%).
void expectHertzSphereTargets(const VerifiedRun& r, double h) {
  EXPECT_LT(std::abs(r["contact:hertz:force:z"].relativeError), 0.02);
  EXPECT_LT(std::abs(r["contact:hertz:radius"].error), h);
  EXPECT_LT(std::abs(r["contact:hertz:peak_pressure"].relativeError), 0.03);
  EXPECT_LT(std::abs(r["contact:hertz:centre_pressure"].relativeError), 0.03);
}

TEST(VerificationHertz, RigidSphereStasOnTheDeckMesh) {
  // The deck's mesh (m = 8, h = 0.19 = a/5.3) takes 11 s of one core. Measured: P(delta) -0.45%,
  // a -4.7% (0.25 h), p0 -0.75%.
  const VerifiedRun r = runVerificationDeck(kDecks + "hertz_rigid_sphere.deck");
  expectCompleted(r);
  expectHertzSphereTargets(r, elementSize(8));
}

TEST(VerificationHertz, ElasticSphereStsRadiusAndCentrePressure) {
  // The deck's mesh (m = 8) takes 102 s of one core (P(delta) -1.5% there), so this runs m = 6
  // (46 s; the finest level under a minute). Measured at m = 6: a -3.9% (0.15 h), p0 at the centre
  // +0.23%, both targets met. Missed there (not asserted, reported in
  // docs/verification/accuracy.md): P(delta) -2.04% (target 2%; -4.6%, -3.0%, -2.0% at m = 3, 4, 6:
  // the two bodies' hex8 stiffness) and the largest point pressure +22% (target 3%: single STS
  // points near the contact edge of the faceted sphere carry pressure spikes; the centre pressure
  // is exact to 0.3%).
  const VerifiedRun r = runVerificationDeck(kDecks + "hertz_elastic_sphere.deck", meshLevel(6, 8));
  expectCompleted(r);
  EXPECT_LT(std::abs(r["contact:hertz:radius"].error), elementSize(6));
  EXPECT_LT(std::abs(r["contact:hertz:centre_pressure"].relativeError), 0.03);
  // The peak of the nodal pressure (force per tributary area of a slave node), the field a
  // contour plot shows: within 3 % of p0 (measured -0.8 % at m = 8), while the largest point
  // pressure is +20 % at one point of an element at the contact edge that is only partly closed.
  EXPECT_LT(std::abs(r["contact:hertz:peak_nodal_pressure"].relativeError), 0.03);
  RecordProperty("force_relative_error", std::to_string(r["contact:hertz:force:z"].relativeError));
  RecordProperty("peak_pressure_relative_error",
                 std::to_string(r["contact:hertz:peak_pressure"].relativeError));
}

TEST(VerificationHertz, RigidCylinderStasOnTheDeckMesh) {
  // The deck's mesh (m = 16, h = 0.094) runs in about a second. Measured: b -4.3% (0.45 h),
  // p0 -0.41% at the centre and as the largest point pressure.
  const VerifiedRun r = runVerificationDeck(kDecks + "hertz_cylinder.deck");
  expectCompleted(r);
  const double h = elementSize(16);
  EXPECT_LT(std::abs(r["contact:hertz:half_width"].error), h);
  EXPECT_LT(std::abs(r["contact:hertz:centre_pressure"].relativeError), 0.03);
  EXPECT_LT(std::abs(r["contact:hertz:peak_pressure"].relativeError), 0.03);
}

TEST(VerificationCattaneoMindlin, CylinderStickHalfWidthWithinOneElementOfTheDeckMesh) {
  // The deck's mesh (m = 16, 17 s on one core) gives c -7.8% = 0.53 h(16); here m = 8 (6 s)
  // gives -11.5% = 0.073, inside the deck mesh's element width h(16) = 0.094.
  DeckChanges changes = meshLevel(8, 16, {{"thickness", "0.1875"}});
  changes.replace = {{"length=0.09375", "length=0.1875"}};  // the slab is one element thick
  const VerifiedRun r = runVerificationDeck(kDecks + "cattaneo_mindlin_cylinder.deck", changes);
  expectCompleted(r);
  const auto& stick = r["contact:cm:stick_half_width"];
  EXPECT_LT(std::abs(stick.error), elementSize(16));
  // The tangential load reached the partial-slip range the test is about.
  const double ratio =
      stick.samples.back().reference / r["contact:cm:half_width"].samples.back().reference;
  EXPECT_GT(ratio, 0.5);
  EXPECT_LT(ratio, 0.8);
  EXPECT_LT(std::abs(r["contact:cm:centre_pressure"].relativeError), 0.03);
}

TEST(VerificationCattaneoMindlin, CylinderDeckAsCommittedCompletesWithinOneElement) {
  // The committed deck itself (m = 16): it stopped at t = 1.4 on "projection broke down" while
  // the m = 8 test above passed (the projection's round-off floor, nineteenth session). Measured
  // since: c -7.8% = 0.53 h, b -1.8%, p0 -0.06%.
  const VerifiedRun r = runVerificationDeck(kDecks + "cattaneo_mindlin_cylinder.deck");
  expectCompleted(r);
  EXPECT_LT(std::abs(r["contact:cm:stick_half_width"].error), elementSize(16));
  EXPECT_LT(std::abs(r["contact:cm:half_width"].error), elementSize(16));
  EXPECT_LT(std::abs(r["contact:cm:centre_pressure"].relativeError), 0.03);
}

TEST(VerificationCattaneoMindlin, SphereStickRadiusWithinOneElementOfTheDeckMesh) {
  // The deck's mesh (m = 4, 49 s of one core) gives c -12% = 0.24 h; here m = 3 (30 s) gives
  // c -24% = 0.18, inside the deck mesh's element width h(4) = 0.375 (and its own h(3) = 0.5).
  const VerifiedRun r =
      runVerificationDeck(kDecks + "cattaneo_mindlin_sphere.deck", meshLevel(3, 4));
  expectCompleted(r);
  const auto& stick = r["contact:cm:stick_radius"];
  EXPECT_LT(std::abs(stick.error), elementSize(4));
  // The tangential load reached the partial-slip range: c/a = (1 - Q/(mu P))^(1/3) ~ 0.74.
  const double ratio =
      stick.samples.back().reference / r["contact:cm:radius"].samples.back().reference;
  EXPECT_GT(ratio, 0.5);
  EXPECT_LT(ratio, 0.9);
  // Tangential compliance (Q at the measured tangential approach): -4.9% at m = 3, no target.
  RecordProperty("tangential_force_relative_error",
                 std::to_string(r["contact:cm:force:x"].relativeError));
}

TEST(VerificationPatchTest, StsOnMatchingMeshesIsUniform) {
  // Target 1e-3; measured ~1e-10 (round-off of the solver).
  const VerifiedRun r = runVerificationDeck(kDecks + "patch_test_sts_matching.deck");
  expectCompleted(r);
  EXPECT_LT(r["contact:interface:pressure_deviation"].error, 1e-3);
  EXPECT_LT(r["contact:interface:nodal_pressure_deviation"].error, 1e-3);
  EXPECT_LT(std::abs(r["reaction:upper_top:z"].relativeError), 1e-5);
}

TEST(VerificationPatchTest, NonMatchingMeshesReportTheirDeviation) {
  // Not a pass/fail target: the deviations are recorded (see the test's XML output) and the
  // force balance is exact for both kinds. STS: the point tractions oscillate (0.29 at
  // eps_N = 1e6) while the slave nodes' force per tributary area is uniform to 0.5%; NTS: 15%.
  for (const std::string kind : {"sts", "nts"}) {
    const VerifiedRun r = runVerificationDeck(kDecks + "patch_test_" + kind + ".deck");
    expectCompleted(r);
    const double point = r["contact:interface:pressure_deviation"].error;
    const double nodal = r["contact:interface:nodal_pressure_deviation"].error;
    RecordProperty(kind + "_point_pressure_deviation", std::to_string(point));
    RecordProperty(kind + "_nodal_pressure_deviation", std::to_string(nodal));
    EXPECT_LT(std::abs(r["reaction:upper_top:z"].relativeError), 5e-3) << kind;
  }
}

TEST(VerificationPatchTest, StsWithSegmentsOnNonMatchingMeshesIsUniform) {
  // integration=segments (issue 16, part 1): target 1e-6 relative in the point pressure. The same
  // mesh with Gauss points (patch_test_sts.deck, the test above) deviates by 0.29 point-wise and
  // 5.4e-3 node-wise.
  const VerifiedRun r = runVerificationDeck(kDecks + "patch_test_sts_segments.deck");
  expectCompleted(r);
  const double point = r["contact:interface:pressure_deviation"].error;
  const double nodal = r["contact:interface:nodal_pressure_deviation"].error;
  RecordProperty("point_pressure_deviation", std::to_string(point));
  RecordProperty("nodal_pressure_deviation", std::to_string(nodal));
  EXPECT_LT(point, 1e-6);
  EXPECT_LT(nodal, 1e-6);
  EXPECT_LT(std::abs(r["reaction:upper_top:z"].relativeError), 1e-5);
}

// Patch test on matching meshes: the blocks (compliance 2T/(E W^2) = 1e-3) and the penalty
// (1/(eps W^2)) in series, so the force error is F x / (1 + x) with x = E W^2 / (2 T eps), and the
// penetration p / eps_N: both fall like 1/eps_N.
TEST(VerificationPenalty, PatchTestErrorsFallLikeOneOverPenalty) {
  const double linearForce = 1e-3;  // E W^2 d / (2 T) with d = 1e-6
  std::vector<double> penetration, forceError;
  for (double eps : {1e5, 1e6}) {
    DeckChanges changes;
    changes.penaltyScale = eps / 1e6;
    const VerifiedRun r = runVerificationDeck(kDecks + "patch_test_sts_matching.deck", changes);
    expectCompleted(r);
    const auto& contact = r.run.steps.back().pair("interface");
    penetration.push_back(-contact.gap.minCoeff());
    forceError.push_back(linearForce - std::abs(r.run.steps.back().setReaction("upper_top").z()));
  }
  // Exact orders between eps = 1e5 and 1e6: 1 for the penetration (up to the 1% change of the
  // pressure) and log10((0.01/1.01)/(0.001/1.001)) = 0.996 for the force error; SVK's
  // nonlinearity at strain 1e-6 changes the force by 1e-9, 1e-3 of the smaller error.
  EXPECT_NEAR(std::log10(penetration[0] / penetration[1]), 1, 0.005);
  EXPECT_NEAR(std::log10(forceError[0] / forceError[1]), 0.996, 0.002);
}

}  // namespace
}  // namespace cc::test
