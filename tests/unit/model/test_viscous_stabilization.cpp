// Viscous stabilisation (`newton stabilize=C`, model/viscous_stabilization.hpp): the element
// volumes its lumped masses come from, against closed-form volumes; and whole runs of a cube
// that nothing supports, which without it has a singular tangent and with it must move so that
// the viscous forces balance the load (the elastic forces of a free body sum to zero), and
// whose energy balance must account for the viscous work; and the factor a run chooses from
// `stabilize_share`, against one counted from a clamped cube's first step by hand; and
// `stabilize_on_failure`, against the runs with the factor given and without it, and
// `stabilize_on_failure_share` with no step to measure from, against the factor from the
// stiffness counted by hand and the one its first step lowers it to.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cube_decks.hpp"
#include "deck_runner.hpp"
#include "model/viscous_stabilization.hpp"

namespace cc::test {
namespace {

// A square frustum: bottom a x a at z = 0, top b x b at z = h, both centred on the z axis, in
// gmsh's Hex8 order. Its faces are planar, so the trilinear element is the frustum itself.
Eigen::Matrix<double, 3, 8> frustum(double a, double b, double h) {
  Eigen::Matrix<double, 3, 8> corners;
  const double s[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int k = 0; k < 4; ++k) {
    corners.col(k) << s[k][0] * a / 2, s[k][1] * a / 2, 0;
    corners.col(k + 4) << s[k][0] * b / 2, s[k][1] * b / 2, h;
  }
  return corners;
}

TEST(ViscousStabilization, HexahedronVolumeOfAFrustumIsTheClosedForm) {
  const double a = 2.0, b = 0.5, h = 1.5;
  EXPECT_NEAR(hexahedronVolume(frustum(a, b, h)), h * (a * a + a * b + b * b) / 3, 1e-14);
  // A general affine image: the volume scales with the determinant of the linear part.
  Eigen::Matrix3d linear;
  linear << 1.2, 0.3, -0.1, 0.2, 0.9, 0.4, -0.3, 0.1, 1.1;
  const Eigen::Matrix3Xd mapped = linear * frustum(a, b, h);
  EXPECT_NEAR(hexahedronVolume(mapped), linear.determinant() * h * (a * a + a * b + b * b) / 3,
              1e-13);
}

// The solid-shell Hex18 (two Quad9 faces, nodes 0-8 at zeta = -1 and 9-17 at zeta = +1): the
// corners are 0-3 and 9-12; its edge and face nodes must not enter the volume.
TEST(ViscousStabilization, HexahedronVolumeOfASolidShell18UsesItsCorners) {
  const Eigen::Matrix<double, 3, 8> corners = frustum(1.0, 1.0, 0.1);
  Eigen::Matrix3Xd nodes = Eigen::Matrix3Xd::Constant(3, 18, 1e3);  // far off: must not count
  for (int k = 0; k < 4; ++k) {
    nodes.col(k) = corners.col(k);
    nodes.col(9 + k) = corners.col(4 + k);
  }
  EXPECT_NEAR(hexahedronVolume(nodes), 0.1, 1e-15);
}

TEST(ViscousStabilization, ForceAndTangentOfOneElement) {
  const Eigen::Matrix3Xd reference = frustum(1.0, 1.0, 2.0);  // volume 2, 1/4 per node
  Eigen::Matrix3Xd previous = reference, current = reference;
  previous.col(3) += Eigen::Vector3d(0.1, 0, 0);
  current.col(3) += Eigen::Vector3d(0.3, -0.2, 0.05);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(24);
  Eigen::MatrixXd tangent = Eigen::MatrixXd::Zero(24, 24);
  const double factorPerTime = 4.0;  // C / dt
  addViscousForces(hexahedronVolume(reference), current, previous, factorPerTime, force, &tangent);
  const Eigen::Vector3d expected = 4.0 * 0.25 * Eigen::Vector3d(0.2, -0.2, 0.05);
  EXPECT_NEAR((force.segment<3>(9) - expected).norm(), 0, 1e-15);
  EXPECT_NEAR(force.norm(), expected.norm(), 1e-15);  // the other nodes have not moved
  EXPECT_TRUE(tangent.isApprox(Eigen::MatrixXd::Identity(24, 24)));  // 4 * 1/4
  EXPECT_NEAR(viscousWork(hexahedronVolume(reference), current, previous, factorPerTime),
              expected.dot(current.col(3) - previous.col(3)), 1e-15);
}

std::string virtualPath() {
  return std::string(COVCONTACT_SOURCE_DIR) + "/tests/unit/model/free_cube.deck";
}

TEST(ViscousStabilization, AFreeCubeIsSingularWithoutIt) {
  const DeckRun run = runDeckText(freeCubeDeck(""), virtualPath());
  EXPECT_EQ(run.summary.outcome, RunSummary::Outcome::Singular);
  EXPECT_EQ(run.summary.stepsConverged, 0);
  // The message names the free motion and the way to carry the body.
  EXPECT_NE(run.summary.message.find("unconstrained rigid-body motion"), std::string::npos)
      << run.summary.message;
  EXPECT_NE(run.summary.message.find("newton stabilize=C"), std::string::npos)
      << run.summary.message;
}

// The lumped masses counted from the uniform grid of the unit cube (2 x 2 x 2 Hex8): a node at
// the cube's centre belongs to 8 elements of volume 1/8, a face centre to 4, an edge midpoint
// to 2, a corner to 1: m = count / 64. Not from the program's element volumes.
Eigen::VectorXd gridMasses(const Eigen::Matrix3Xd& nodes) {
  Eigen::VectorXd mass(nodes.cols());
  for (Eigen::Index i = 0; i < nodes.cols(); ++i) {
    int inner = 0;  // coordinates at 0.5: the node is shared along that axis
    for (int c = 0; c < 3; ++c) inner += std::abs(nodes(c, i) - 0.5) < 1e-12 ? 1 : 0;
    mass[i] = std::pow(2.0, inner) / 64;
  }
  return mass;
}

// With it, each node's viscous force is C m_i du_i / dt, and the elastic forces of the free body
// sum to zero, so sum_i C m_i du_i / dt must equal the load's total 10 t, component by component.
TEST(ViscousStabilization, AFreeCubeMovesSoThatTheViscousForcesCarryTheLoad) {
  const double factor = 0.5, dt = 0.25;
  const DeckRun run = runDeckText(freeCubeDeck("  newton stabilize=0.5\n"), virtualPath());
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed);
  ASSERT_EQ(run.steps.size(), 4u);
  const Eigen::Matrix3Xd& nodes = run.model->mesh().coordinates;
  const Eigen::VectorXd mass = gridMasses(nodes);
  ASSERT_NEAR(mass.sum(), 1.0, 1e-14);
  Eigen::Matrix3Xd before = Eigen::Matrix3Xd::Zero(3, nodes.cols());
  for (const RecordedStep& step : run.steps) {
    SCOPED_TRACE(step.step);
    const Eigen::Vector3d viscous =
        factor / dt * ((step.displacement - before) * mass.asDiagonal()).rowwise().sum();
    EXPECT_NEAR(viscous.x(), 0, 1e-9);
    EXPECT_NEAR(viscous.y(), 0, 1e-9);
    EXPECT_NEAR(viscous.z(), 10 * step.time, 1e-9 * 10 * step.time);
    before = step.displacement;
  }
}

// Given on a `steps` line, the factor holds for that phase only: the next phase, without it,
// meets the free cube's singular tangent in its first step.
TEST(ViscousStabilization, OnAStepsLineItHoldsForThatPhaseOnly) {
  const DeckRun run = runDeckText(
      freeCubeDeck("", "10*t", "2 dt=0.25 stabilize=0.5\n  steps 2 dt=0.25"), virtualPath());
  EXPECT_EQ(run.summary.outcome, RunSummary::Outcome::Singular);
  EXPECT_EQ(run.summary.stepsConverged, 2);
}

// The work of the load (trapezoidal rule) against the stored energy plus the viscous work (the
// backward-Euler force times each step's increment): they differ by the time integration's error
// only, which the quadrature bound measures. A constant force of 10 from the first step on, 20
// steps: the bound is half the first step's work, and the viscous forces take most of the rest,
// so the check is not empty.
TEST(ViscousStabilization, TheEnergyBalanceCountsTheViscousWork) {
  const DeckRun run =
      runDeckText(freeCubeDeck("  newton stabilize=0.5\n", "10", "20 dt=0.05"), virtualPath());
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed);
  const EnergyRecord& last = run.steps.back().energy;
  EXPECT_GT(last.stabilizationDissipation, 0.5 * last.externalWork);
  for (const RecordedStep& step : run.steps) {
    SCOPED_TRACE(step.step);
    EXPECT_LE(std::abs(step.energy.balance), step.energy.quadratureBound);
  }
  // Without the viscous work the balance would be off by it.
  EXPECT_GT(last.stabilizationDissipation, 10 * last.quadratureBound);
}

// The load's nodal shares on the top face: `total` splits it equally over the set's 9 nodes.
Eigen::VectorXd topLoadShares(const Eigen::Matrix3Xd& nodes) {
  Eigen::VectorXd share = Eigen::VectorXd::Zero(nodes.cols());
  for (Eigen::Index i = 0; i < nodes.cols(); ++i) {
    if (std::abs(nodes(2, i) - 1) < 1e-12) share[i] = 1.0 / 9;
  }
  return share;
}

// stabilize_share=F: the phase's first step is solved without stabilisation, and the factor
// then makes a step like it dissipate F of its work: C = F W_1 dt / sum_i m_i |du_i|^2. W_1 is
// the load's work over step 1 by the trapezoidal rule (the clamped nodes do none), counted here
// from the nodal loads; the factor must be the one the later steps were solved with, which the
// same deck with that factor given from step 2 on shows, to the solver's round-off.
TEST(ViscousStabilization, AShareSetsTheFactorFromThePhasesFirstStep) {
  const double share = 0.05, dt = 0.25;
  const DeckRun chosen =
      runDeckText(clampedCubeDeck("  steps 4 dt=0.25 stabilize_share=0.05\n"), virtualPath());
  ASSERT_EQ(chosen.summary.outcome, RunSummary::Outcome::Completed);
  ASSERT_EQ(chosen.steps.size(), 4u);
  const Eigen::Matrix3Xd& nodes = chosen.model->mesh().coordinates;
  const Eigen::VectorXd mass = gridMasses(nodes);
  const Eigen::Matrix3Xd& first = chosen.steps[0].displacement;
  const double work = 0.5 * 10 * dt * first.row(2).dot(topLoadShares(nodes));
  const double unitDissipation = first.colwise().squaredNorm().dot(mass) / dt;
  const double factor = share * work / unitDissipation;
  EXPECT_EQ(chosen.steps[0].energy.stabilizationDissipation, 0.0);

  // Step 2's dissipation, from the displacements: the factor the run applied.
  const Eigen::Matrix3Xd second = chosen.steps[1].displacement - first;
  const double applied = chosen.steps[1].energy.stabilizationDissipation /
                         (second.colwise().squaredNorm().dot(mass) / dt);
  EXPECT_NEAR(applied, factor, 1e-12 * factor);

  const DeckRun given =
      runDeckText(clampedCubeDeck(fmt::format(
                      "  steps 1 dt=0.25\n  steps 3 dt=0.25 stabilize={:.17g}\n", factor)),
                  virtualPath());
  ASSERT_EQ(given.steps.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    SCOPED_TRACE(k + 1);
    EXPECT_LT((chosen.steps[k].displacement - given.steps[k].displacement).norm(),
              1e-12 * given.steps[k].displacement.norm());
  }
  // The viscous force resists the pull: the stabilised top moves less than without it.
  const DeckRun plain = runDeckText(clampedCubeDeck("  steps 4 dt=0.25\n"), virtualPath());
  EXPECT_LT(chosen.steps[1].displacement.row(2).maxCoeff(),
            plain.steps[1].displacement.row(2).maxCoeff());
}

// stabilize_on_failure=C: a step is stabilised only after it failed without, and the steps
// after it until grow_after (3) of them converged easily. The free cube's every step is
// singular without it: step 1 fails and is retried with the factor, steps 2-3 keep it, step 3
// is the third easy one, so step 4 tries without again, fails and is retried. Every step is
// then solved with the factor from the same start as in the run with stabilize=C, whose steps
// the closed form above checks.
TEST(ViscousStabilization, OnFailureAFreeCubeIsCarriedAsWithTheFactorGiven) {
  const DeckRun retried =
      runDeckText(freeCubeDeck("  newton stabilize_on_failure=0.5\n"), virtualPath());
  ASSERT_EQ(retried.summary.outcome, RunSummary::Outcome::Completed) << retried.summary.message;
  EXPECT_EQ(retried.summary.stabilizedRetries, 2);
  EXPECT_EQ(retried.summary.totalCutbacks, 0);
  const DeckRun given = runDeckText(freeCubeDeck("  newton stabilize=0.5\n"), virtualPath());
  ASSERT_EQ(retried.steps.size(), given.steps.size());
  for (std::size_t k = 0; k < given.steps.size(); ++k) {
    SCOPED_TRACE(k + 1);
    EXPECT_EQ(retried.steps[k].iterations, given.steps[k].iterations);
    EXPECT_LT((retried.steps[k].displacement - given.steps[k].displacement).norm(),
              1e-12 * given.steps[k].displacement.norm());
    EXPECT_NEAR(retried.steps[k].energy.stabilizationDissipation,
                given.steps[k].energy.stabilizationDissipation,
                1e-12 * given.steps[k].energy.stabilizationDissipation);
  }
}

// stabilize_on_failure_share=F with no step converged without stabilisation to measure the
// factor from: the free cube fails its first step, so the factor comes from the stiffness,
// C = F E dt / L^2 with the deck's E = 100, its step 0.25 and the unit cube's side L = 1: step 1
// must be the one with that factor given, and its retry must say where C came from. A free
// body's motion dissipates more than F of its work (the viscous forces alone carry the load), so
// step 2 is solved with the factor step 1 measures, C = F W_1 dt / sum_i m_i |du_i|^2, counted
// here from the nodal loads and the grid's masses as for stabilize_share above.
TEST(ViscousStabilization, OnFailureShareWithNoStepToMeasureTakesTheFactorFromTheStiffness) {
  const double share = 0.05, youngs = 100, dt = 0.25, side = 1;
  const double factor = share * youngs * dt / (side * side);
  const DeckRun chosen =
      runDeckText(freeCubeDeck(fmt::format("  newton stabilize_on_failure_share={:g}\n", share)),
                  virtualPath());
  ASSERT_EQ(chosen.summary.outcome, RunSummary::Outcome::Completed) << chosen.summary.message;
  ASSERT_EQ(chosen.steps.size(), 4u);
  ASSERT_FALSE(chosen.cutbacks.empty());
  EXPECT_NE(chosen.cutbacks.front().reason.find(
                fmt::format("C = {:.4g} from the stiffness of 'cube' (E = 100, size 1)", factor)),
            std::string::npos)
      << chosen.cutbacks.front().reason;
  const DeckRun given =
      runDeckText(freeCubeDeck(fmt::format("  newton stabilize_on_failure={:.17g}\n", factor),
                               "10*t", "1 dt=0.25"),
                  virtualPath());
  ASSERT_EQ(given.steps.size(), 1u);
  const Eigen::Matrix3Xd& first = chosen.steps[0].displacement;
  EXPECT_LT((first - given.steps[0].displacement).norm(),
            1e-12 * given.steps[0].displacement.norm());

  const Eigen::Matrix3Xd& nodes = chosen.model->mesh().coordinates;
  const Eigen::VectorXd mass = gridMasses(nodes);
  const double work = 0.5 * 10 * dt * first.row(2).dot(topLoadShares(nodes));
  const double lowered = share * work / (first.colwise().squaredNorm().dot(mass) / dt);
  EXPECT_LT(lowered, factor);
  const Eigen::Matrix3Xd second = chosen.steps[1].displacement - first;
  const double dissipated = chosen.steps[1].energy.stabilizationDissipation -
                            chosen.steps[0].energy.stabilizationDissipation;
  const double applied = dissipated / (second.colwise().squaredNorm().dot(mass) / dt);
  EXPECT_NEAR(applied, lowered, 1e-12 * lowered);
}

// A step that converges without stabilisation is the quasi-static problem's, bit for bit.
TEST(ViscousStabilization, OnFailureAStepThatConvergesIsNotStabilized) {
  const DeckRun retried = runDeckText(
      clampedCubeDeck("  newton stabilize_on_failure=0.5\n  steps 4 dt=0.25\n"), virtualPath());
  const DeckRun plain = runDeckText(clampedCubeDeck("  steps 4 dt=0.25\n"), virtualPath());
  ASSERT_EQ(retried.summary.outcome, RunSummary::Outcome::Completed);
  EXPECT_EQ(retried.summary.stabilizedRetries, 0);
  ASSERT_EQ(retried.steps.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    SCOPED_TRACE(k + 1);
    EXPECT_EQ(retried.steps[k].displacement, plain.steps[k].displacement);
    EXPECT_EQ(retried.steps[k].energy.stabilizationDissipation, 0.0);
  }
}

}  // namespace
}  // namespace cc::test
