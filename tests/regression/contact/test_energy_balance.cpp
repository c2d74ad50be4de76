// Frictional dissipation and the energy balance of whole runs (issue 16, part 4): the
// dissipation power of a sliding block against mu N v, and the balance W_ext = E_strain +
// E_contact + D against the step-size error of its time integration.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>

#include "deck_runner.hpp"

namespace cc::test {
namespace {

const std::string kSourceDir = COVCONTACT_SOURCE_DIR;

bool allContactPointsSlide(const ContactPairRecord& pair) {
  int inContact = 0;
  for (int i = 0; i < pair.state.size(); ++i) {
    if (pair.state[i] == static_cast<int>(ContactState::Open)) continue;
    ++inContact;
    if (pair.state[i] != static_cast<int>(ContactState::Slip)) return false;
  }
  return inContact > 0;
}

// A block dragged on a fixed flat base (input/verification/contact/block_on_fixed_base.deck):
// once every point slides and the block only translates, the slip of a step is the drag of the
// top, 2e-3 per unit time, and the dissipation power must be mu |N| v with N the pair's total
// normal force. Both sides are computed independently (per-point return-mapping slips and
// tractions against the summed force and the prescribed motion); they agree to the Newton
// tolerance once the block's elastic state is steady.
TEST(EnergyBalance, DissipationPowerIsMuTimesNormalForceTimesSlipRate) {
  const DeckRun run =
      runDeckFile(kSourceDir + "/input/verification/contact/block_on_fixed_base.deck");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed);
  const double mu = 0.3, velocity = 2e-3;
  int checked = 0;
  for (std::size_t k = 1; k < run.steps.size(); ++k) {
    const ContactPairRecord& previous = run.steps[k - 1].pair("interface");
    const ContactPairRecord& pair = run.steps[k].pair("interface");
    if (!allContactPointsSlide(previous) || !allContactPointsSlide(pair)) continue;
    const double expected = mu * std::abs(pair.totalForce.y()) * velocity;
    SCOPED_TRACE(run.steps[k].step);
    EXPECT_NEAR(pair.dissipationPower, expected, 1e-6 * expected);
    EXPECT_NEAR(run.steps[k].energy.dissipationPower, expected, 1e-6 * expected);
    EXPECT_NEAR(pair.stepDissipation.sum(), pair.dissipation, 1e-12 * expected);
    ++checked;
  }
  EXPECT_GE(checked, 3);
}

// Paper example 6.1(a) (block on an elastic base, pressed in one step, then dragged in 100
// steps of 2.5e-4 into gross sliding): the work of the loads and reactions equals the stored
// strain energy plus the penalty energy plus the frictional dissipation. The trapezoidal work
// and the backward-Euler dissipation err by O(step^2) per step; the per-step bound
// |(F_{n+1} - F_n) . Delta u| / 2 (the trapezoidal against a one-sided rule) is the tolerance,
// step by step and summed over the drag, and it is itself below 1 % of the drag work, so the
// check is not empty. (The press, a single step from zero load, has a bound as large as its
// work; it is checked against it too, and the drag is checked relative to its end.)
TEST(EnergyBalance, ClosesOnSlidingBlockExample61a) {
  const DeckRun run = runDeckFile(kSourceDir + "/input/paper/sliding_block_6_1a.deck");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed);
  ASSERT_GT(run.steps.size(), 2u);
  const EnergyRecord& press = run.steps.front().energy;
  ASSERT_TRUE(std::isfinite(press.strainEnergy));
  EXPECT_LE(std::abs(press.balance), press.quadratureBound);
  for (std::size_t k = 1; k < run.steps.size(); ++k) {
    const EnergyRecord& before = run.steps[k - 1].energy;
    const EnergyRecord& e = run.steps[k].energy;
    SCOPED_TRACE(run.steps[k].step);
    EXPECT_LE(std::abs(e.balance - before.balance), e.quadratureBound - before.quadratureBound);
  }
  const EnergyRecord& last = run.steps.back().energy;
  const double dragWork = last.externalWork - press.externalWork;
  const double dragBound = last.quadratureBound - press.quadratureBound;
  EXPECT_LE(std::abs(last.balance - press.balance), dragBound);
  EXPECT_LE(dragBound, 1e-2 * dragWork);
  // Gross sliding dissipates most of the drag work.
  EXPECT_GT(last.dissipation - press.dissipation, 0.8 * dragWork);
}

// A thin solid-shell strip bent by a rigid cylinder that moves up (input/stress/
// thin_shell_on_cylinder.deck, STAS, frictionless): all the work enters through the moving rigid
// surface, and all of it is stored in the solid-shells (with their assumed and enhanced strains)
// and the penalty springs. The balance must close within the quadrature bound at every step and
// over every step, the bound being itself below 2 % of the work. The deck's steps are taken 8
// times smaller: the trapezoidal bound falls with the step, 11 % of the work with the deck's own
// 10 steps and 2.8 % with steps 4 times smaller, too loose to test anything.
// Before, the rigid surface's work was not booked (W_ext = 0) and the solid-shells' strain
// energy was NaN.
std::string textOf(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(EnergyBalance, ClosesWhenAMovingRigidSurfaceBendsSolidShells) {
  const std::string path = kSourceDir + "/input/stress/thin_shell_on_cylinder.deck";
  std::string deck = textOf(path);
  for (const auto& [coarse, fine] : {std::pair{"steps 5 dt=0.0025", "steps 40 dt=0.0003125"},
                                     std::pair{"steps 5 dt=0.0015", "steps 40 dt=0.0001875"}}) {
    const std::size_t at = deck.find(coarse);
    ASSERT_NE(at, std::string::npos) << coarse;
    deck.replace(at, std::string(coarse).size(), fine);
  }
  const DeckRun run = runDeckText(deck, path);
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed);
  ASSERT_EQ(run.steps.size(), 80u);
  double previousBalance = 0, previousBound = 0;
  for (const RecordedStep& step : run.steps) {
    const EnergyRecord& e = step.energy;
    SCOPED_TRACE(step.step);
    ASSERT_TRUE(std::isfinite(e.strainEnergy));
    EXPECT_LE(std::abs(e.balance), e.quadratureBound);
    EXPECT_LE(std::abs(e.balance - previousBalance), e.quadratureBound - previousBound);
    previousBalance = e.balance;
    previousBound = e.quadratureBound;
  }
  const EnergyRecord& last = run.steps.back().energy;
  EXPECT_GT(last.externalWork, 0.0);
  EXPECT_LE(last.quadratureBound, 2e-2 * last.externalWork);
  EXPECT_NEAR(last.externalWork, last.strainEnergy + last.contactEnergy, last.quadratureBound);
}

// Paper example 6.1(b) in gross sliding (steps of 12e-3): the dissipation of a step against
// mu N Delta u, N = sum of w |N| over the points (on the deformed base the normals tilt, so N is
// not |F_y|). On the elastic base the slip of the contact points differs from the drag of the
// top: the energy balance of the step, |F_x| Delta u = D + Delta E_strain + Delta E_contact, makes
// the tolerance |Delta E_strain| + |Delta E_contact| + ||F_x| - mu N| Delta u (the tilted normals
// and tractions) plus the step's quadrature bound; it is below 1e-3 of D.
TEST(EnergyBalance, DissipationInGrossSlidingOfExample61b) {
  const DeckRun run = runDeckFile(kSourceDir + "/input/paper/sliding_block_6_1b_exact.deck");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed);
  const double mu = 0.3, drag = 12e-3;
  int checked = 0;
  for (std::size_t k = 1; k < run.steps.size(); ++k) {
    const ContactPairRecord& pair = run.steps[k].pair("interface");
    if (!allContactPointsSlide(run.steps[k - 1].pair("interface")) || !allContactPointsSlide(pair))
      continue;
    const EnergyRecord& before = run.steps[k - 1].energy;
    const EnergyRecord& e = run.steps[k].energy;
    double tolerance = std::abs(e.strainEnergy - before.strainEnergy) +
                       std::abs(e.contactEnergy - before.contactEnergy) +
                       (e.quadratureBound - before.quadratureBound);
    SCOPED_TRACE(run.steps[k].step);
    const double normalForce = pair.weight.dot(pair.normalTraction.cwiseAbs());
    tolerance += std::abs(std::abs(pair.totalForce.x()) - mu * normalForce) * drag;
    EXPECT_NEAR(pair.dissipation, mu * normalForce * drag, tolerance);
    EXPECT_LE(tolerance, 1e-3 * pair.dissipation);
    ++checked;
  }
  EXPECT_GE(checked, 5);
}

}  // namespace
}  // namespace cc::test
