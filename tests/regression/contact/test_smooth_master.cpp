// Smoothed master surfaces in whole runs (issue 16, part 2): paper example 6.3's semi-cylinder
// on a meshed parabolic trough (input/verification/smooth_master, nx = 8 segments along the
// sliding direction), faceted and smoothed (Nagata), against the same run on the analytic
// surface (STAS). The targets of the issue that the smoothing meets are asserted here with the
// measure of scripts/smooth_master_table.py (docs/verification/smooth_master.md): the force
// oscillation at segment crossings reduced at least 10 times against the faceted master, no
// more Newton iterations per step than on the analytic surface; the smoothed run's force is
// mesh-converged where the faceted one is not, and it obeys Coulomb's law in gross sliding.
// A master with a sharp edge keeps it when smoothed (creases): the faceted run's forces.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "deck_runner.hpp"

namespace cc::test {
namespace {

const std::string kDecks =
    std::string(COVCONTACT_SOURCE_DIR) + "/input/verification/smooth_master/";

// Gross sliding, steps 5 to 36 (1: press; smooth_master_table.py says why 36) and the window
// of the local quadratic trend removed before the peak-to-peak.
constexpr int kFirstGross = 5, kLastGross = 36, kWindow = 7;

struct History {
  std::vector<double> time;
  std::vector<Eigen::Vector3d> force;  // on the driven edges
  double iterationsPerSpiralStep = 0;
};

History historyOf(const std::string& deck) {
  const DeckRun run = runDeckFile(kDecks + deck);
  EXPECT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << deck;
  History h;
  int spiralIterations = 0;
  for (const RecordedStep& step : run.steps) {
    EXPECT_EQ(step.cutbacks, 0) << deck << " step " << step.step;
    h.time.push_back(step.time);
    h.force.push_back(step.setReaction("top_edges"));
    if (step.step > 1) spiralIterations += step.iterations;
  }
  h.iterationsPerSpiralStep = double(spiralIterations) / (run.steps.size() - 1);
  return h;
}

// Peak-to-peak over gross sliding of F_c - F_analytic,c minus its local quadratic trend, over
// the mean |F_analytic,c|; the largest over c = x, y, z.
double oscillation(const History& run, const History& analytic) {
  double worst = 0;
  const int half = kWindow / 2;
  for (int c = 0; c < 3; ++c) {
    double low = 1e300, high = -1e300, mean = 0;
    for (int k = kFirstGross - 1; k < kLastGross; ++k) mean += std::abs(analytic.force[k][c]);
    mean /= kLastGross - kFirstGross + 1;
    for (int k = kFirstGross - 1 + half; k < kLastGross - half; ++k) {
      Eigen::MatrixXd A(kWindow, 3);
      Eigen::VectorXd d(kWindow);
      for (int j = 0; j < kWindow; ++j) {
        const double u =
            (run.time[k - half + j] - run.time[k]) / (run.time[k + half] - run.time[k]);
        A.row(j) << 1, u, u * u;
        d[j] = run.force[k - half + j][c] - analytic.force[k - half + j][c];
      }
      const Eigen::Vector3d trend = A.colPivHouseholderQr().solve(d);
      const double residual = d[half] - trend[0];
      low = std::min(low, residual);
      high = std::max(high, residual);
    }
    worst = std::max(worst, (high - low) / mean);
  }
  return worst;
}

// max over the spiral of |F - F_reference| / |F_reference|.
double forceDifference(const History& run, const History& reference) {
  double worst = 0;
  for (std::size_t k = 1; k < run.force.size(); ++k) {
    worst = std::max(worst, (run.force[k] - reference.force[k]).norm() / reference.force[k].norm());
  }
  return worst;
}

// Largest deviation over gross sliding from Coulomb's law, an independent reference: the force
// of the trough on the shell must be mu N against the slip, with n the parabola's normal at the
// foot point of the prescribed motion (the contact line; model.inc: the edges keep the exact
// 0.99-offset of the foot point (a, c a^2), a = 0.01 (t - 1)) and the slip the tangential part
// of the edges' prescribed displacement in the step. Returns (| |F_t| / (mu N) - 1 |, angle).
std::pair<double, double> coulombDeviation(const History& run) {
  constexpr double mu = 0.3, c = 0.05;
  auto position = [](double t, double& a) {
    a = 0.01 * std::max(t - 1, 0.0);
    const double q = std::sqrt(1 + 4 * c * c * a * a);
    return Eigen::Vector3d(a * (1 - 2 * c * 0.99 / q), 0.02 * std::max(t - 1, 0.0),
                           -0.01 * std::min(t, 1.0) + c * a * a + 0.99 / q - 0.99);
  };
  double ratio = 0, angle = 0;
  for (int k = kFirstGross - 1; k < kLastGross; ++k) {
    double a = 0, previousA = 0;
    const Eigen::Vector3d slip = position(run.time[k], a) - position(run.time[k - 1], previousA);
    const Eigen::Vector3d n = Eigen::Vector3d(-2 * c * a, 0, 1).normalized();
    const Eigen::Vector3d force = -run.force[k];  // on the shell, from the trough
    const double normal = force.dot(n);
    const Eigen::Vector3d tangential = force - normal * n;
    const Eigen::Vector3d slipTangential = slip - slip.dot(n) * n;
    ratio = std::max(ratio, std::abs(tangential.norm() / (mu * normal) - 1));
    angle = std::max(
        angle, std::acos(std::min(1.0, -tangential.normalized().dot(slipTangential.normalized()))));
  }
  return {ratio, angle};
}

TEST(smooth_master, contact_6_3_on_meshed_trough_against_analytic) {
  const History analytic = historyOf("analytic.deck");
  const History faceted = historyOf("trough_nx8_faceted.deck");
  const History smooth = historyOf("trough_nx8_smooth.deck");
  const History finer = historyOf("trough_nx16_smooth.deck");
  ASSERT_EQ(faceted.time.size(), analytic.time.size());
  ASSERT_EQ(smooth.time.size(), analytic.time.size());
  const double facetedOscillation = oscillation(faceted, analytic);
  const double smoothOscillation = oscillation(smooth, analytic);
  // Measured: 14.7 % against 0.30 % (docs/verification/smooth_master.md).
  EXPECT_GE(facetedOscillation, 10 * smoothOscillation)
      << facetedOscillation << " " << smoothOscillation;
  // Measured: 5.175 and 5.175 iterations per spiral step.
  EXPECT_LE(smooth.iterationsPerSpiralStep, analytic.iterationsPerSpiralStep);
  // Mesh convergence (h = 0.5 against 0.25): smooth 0.07 %, faceted 45 %.
  EXPECT_LT(forceDifference(smooth, finer), 2e-3);
  EXPECT_GT(forceDifference(faceted, finer), 0.1);
  // Coulomb's law: measured 1.1 % and 1.4 degrees (the normal at the foot point stands for the
  // contact zone's), faceted 3.9 % and 4.5 degrees, and 13.6 % and 12.2 degrees for the STAS
  // reference at this shell mesh (nt = 16), which keeps the force history 8 % from it; with the
  // shell resolved both agree (the test below).
  const auto [smoothRatio, smoothAngle] = coulombDeviation(smooth);
  const auto [facetedRatio, facetedAngle] = coulombDeviation(faceted);
  EXPECT_LT(smoothRatio, 0.02);
  EXPECT_LT(smoothAngle, 2.0 * M_PI / 180);
  EXPECT_GT(facetedRatio, 2 * smoothRatio);
  EXPECT_GT(facetedAngle, 2 * smoothAngle);
}

// The target "force history within 1 % of the analytic-surface run at a moderate mesh" needs
// the shell resolved: with nt = 16 elements around the semi-cylinder the contact zone is
// narrower than a shell element, and the meshed (sts) and analytic (stas) runs, which integrate
// differently over that zone, differ by 7-8 % at every trough density, the analytic one off
// Coulomb's law by 13.6 %. With nt = 64 (the *_nt64 decks) the smoothed coarsest trough (nx = 8,
// h = 0.5) follows the analytic run to 0.15 % (faceted 30 %), with no more Newton iterations,
// and the analytic run obeys Coulomb's law to 0.5 % and 0.5 degrees (measured; smooth_master.md).
TEST(smooth_master, resolved_shell_follows_the_analytic_surface_within_one_percent) {
  const History analytic = historyOf("analytic_nt64.deck");
  const History smooth = historyOf("trough_nx8_smooth_nt64.deck");
  ASSERT_EQ(smooth.time.size(), analytic.time.size());
  EXPECT_LT(forceDifference(smooth, analytic), 0.01);
  EXPECT_LE(smooth.iterationsPerSpiralStep, analytic.iterationsPerSpiralStep);
  const auto [ratio, angle] = coulombDeviation(analytic);
  EXPECT_LT(ratio, 0.01);
  EXPECT_LT(angle, 1.0 * M_PI / 180);
}

// A master with a sharp edge (block_corner*.deck: the stiff block's bottom and right side, 90
// degrees apart): smoothed with its default crease angle the edge stays sharp, and with faces
// that barely bend the forces on the block are the faceted master's to 1e-4, step by step
// (measured 2.3e-5: the curvature the block's bending gives the smoothed faces). The same
// smoothing without creases (crease=180) rounds the edge, and the forces change by more than
// half: the check fails if the edge is not kept.
TEST(smooth_master, a_box_edge_stays_sharp) {
  const auto blockForces = [](const std::string& deck) {
    const DeckRun run = runDeckFile(kDecks + deck);
    EXPECT_EQ(run.summary.outcome, RunSummary::Outcome::Completed) << deck;
    std::vector<Eigen::Vector3d> forces;
    for (const RecordedStep& step : run.steps) forces.push_back(step.setReaction("block_top"));
    return forces;
  };
  const auto faceted = blockForces("block_corner_faceted.deck");
  const auto smooth = blockForces("block_corner_smooth.deck");
  const auto rounded = blockForces("block_corner_rounded.deck");
  ASSERT_EQ(faceted.size(), 7u);
  ASSERT_EQ(smooth.size(), faceted.size());
  ASSERT_EQ(rounded.size(), faceted.size());
  double kept = 0, lost = 0;
  for (std::size_t k = 0; k < faceted.size(); ++k) {
    kept = std::max(kept, (smooth[k] - faceted[k]).norm() / faceted[k].norm());
    lost = std::max(lost, (rounded[k] - faceted[k]).norm() / faceted[k].norm());
  }
  EXPECT_LT(kept, 1e-4);
  EXPECT_GT(lost, 0.5);
}

}  // namespace
}  // namespace cc::test
