// Newton: the FEAP predictor (K_fp du_p) solves a linear chain in one iteration; a hardening
// chain converges quadratically to its closed-form solution with the documented iteration
// counts per criterion; line search and divergence detection.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "solver/newton.hpp"
#include "spring_chain.hpp"

namespace cc {
namespace {

using test::RecordingObserver;
using test::SpringChain;
using test::SpringLaw;
using test::SwitchingChain;

NewtonResult solveStep(SpringChain& chain, RecordingObserver& observer, const NewtonSpec& spec,
                       Eigen::VectorXd& displacement, double time, double previousTime = 0) {
  Newton newton(chain, observer, Newton::Clock::now());
  return newton.solve({1, 0, time, previousTime}, spec, displacement);
}

NewtonSpec withCriterion(NewtonSpec::Criterion criterion) {
  NewtonSpec spec;
  spec.criterion = criterion;
  return spec;
}

TEST(Newton, PrescribedEndOfLinearChainSolvedByThePredictor) {
  const int springs = 5;
  const double stiffness = 2.0, endDisplacement = 0.5;
  for (auto criterion : {NewtonSpec::Criterion::Residual, NewtonSpec::Criterion::Energy}) {
    SpringChain chain(springs, SpringLaw::linear(stiffness),
                      [&](double t) { return endDisplacement * t; });
    RecordingObserver observer;
    Newton newton(chain, observer, Newton::Clock::now());
    Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * (springs + 1));
    const NewtonResult result = newton.solve({1, 0, 1.0, 0.0}, withCriterion(criterion), u);
    ASSERT_EQ(result.status, NewtonResult::Status::Converged) << result.message;
    // Residual: seen at the start of iteration 2 -> 1; Energy: FEAP's confirming solve -> 2.
    EXPECT_EQ(result.iterations, criterion == NewtonSpec::Criterion::Residual ? 1 : 2);
    for (int node = 0; node <= springs; ++node) {
      EXPECT_NEAR(u[3 * node], endDisplacement * node / springs, 1e-14);
    }
    // Force at the displaced end (the reaction): k D / n.
    EXPECT_NEAR(newton.internalForce()[3 * springs], stiffness * endDisplacement / springs, 1e-14);
  }
}

// The relative residual an iterative linear solve is asked for (newton.hpp): kForcingMax at the
// first iteration of a step's first attempt, kRetryFirstForcing at the first iteration of an
// attempt after a failed one (on the refined ironing die the first solve at 1e-3 set a path on
// which Newton stalled, retries included), and from the second iteration on Eisenstat and
// Walker's choice, at most 100 times the relative residual. A direct solve reports none.
TEST(Newton, TheFirstIterativeSolveOfARetryIsAskedForMore) {
  for (const int attempt : {0, 1}) {
    SCOPED_TRACE(attempt);
    // Pulled by an end force that stretches each spring by about 1: several iterations.
    SpringChain chain(5, SpringLaw::cubic(2.0, 1.0), {}, [](double t) { return 4.0 * t; });
    RecordingObserver observer;
    LinearSolverSpec amg;
    amg.method = LinearSolverSpec::Method::Amg;
    Newton newton(chain, observer, Newton::Clock::now(), amg);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * 6);
    const NewtonResult result = newton.solve({1, attempt, 1.0, 0.0}, NewtonSpec{}, u);
    ASSERT_EQ(result.status, NewtonResult::Status::Converged) << result.message;
    ASSERT_GE(observer.iterations.size(), 3u);
    EXPECT_EQ(observer.iterations[0].krylovTolerance,
              attempt == 0 ? kForcingMax : kRetryFirstForcing);
    for (std::size_t k = 0; k < observer.iterations.size(); ++k) {
      const IterationRecord& r = observer.iterations[k];
      EXPECT_GT(r.krylovIterations, 0);
      if (k > 0) {
        EXPECT_LE(r.krylovTolerance, kForcingResidualFactor * r.relativeResidual * (1 + 1e-12));
        EXPECT_GE(r.krylovTolerance, kForcingMin);
      }
    }
  }
  SpringChain chain(5, SpringLaw::cubic(2.0, 1.0), {}, [](double t) { return 4.0 * t; });
  RecordingObserver observer;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * 6);
  ASSERT_EQ(solveStep(chain, observer, NewtonSpec{}, u, 1.0).status,
            NewtonResult::Status::Converged);
  for (const IterationRecord& r : observer.iterations) {
    EXPECT_EQ(r.krylovTolerance, 0.0);
    EXPECT_EQ(r.krylovIterations, 0);
  }
}

// The configuration a step starts from (AssemblyState::previous, x_n of the viscous
// stabilisation): a re-solve of the same attempt starts from the first solve's solution but
// keeps the first solve's x_n; a new attempt starts afresh.
struct StartRecordingChain : SpringChain {
  using SpringChain::SpringChain;
  std::vector<double> starts;  // x of the end node at x_n, per assembly
  void assemble(const AssemblyState& state, Eigen::VectorXd& internalForce,
                SystemMatrices* tangent) override {
    starts.push_back((*state.previous)(0, state.previous->cols() - 1));
    SpringChain::assemble(state, internalForce, tangent);
  }
};

TEST(Newton, AReSolveOfTheSameAttemptKeepsTheStepsStart) {
  StartRecordingChain chain(3, SpringLaw::cubic(1.0, 1.0),
                            [](double t) { return 0.2 * std::min(t, 1.0); });
  RecordingObserver observer;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(12);
  Newton newton(chain, observer, Newton::Clock::now());
  const double start = chain.referenceCoordinates()(0, 3);  // the end node at u = 0
  ASSERT_EQ(newton.solve({1, 0, 1.0, 0.0}, NewtonSpec{}, u).status,
            NewtonResult::Status::Converged);
  ASSERT_GT(std::abs(u[9]), 0.1);  // the end node moved
  chain.starts.clear();
  ASSERT_EQ(newton.solve({1, 0, 1.0, 0.0}, NewtonSpec{}, u).status,
            NewtonResult::Status::Converged);
  ASSERT_FALSE(chain.starts.empty());
  for (double x : chain.starts) EXPECT_EQ(x, start);
  chain.starts.clear();
  ASSERT_EQ(newton.solve({1, 1, 1.0, 0.0}, NewtonSpec{}, u).status,
            NewtonResult::Status::Converged);
  for (double x : chain.starts) EXPECT_EQ(x, start + u[9]);
}

TEST(Newton, StepStartingInEquilibriumTakesOneIteration) {
  SpringChain chain(3, SpringLaw::cubic(1.0, 1.0), [](double t) { return 0.2 * std::min(t, 1.0); });
  RecordingObserver observer;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(12);
  Newton newton(chain, observer, Newton::Clock::now());
  ASSERT_EQ(newton.solve({1, 0, 1.0, 0.0}, NewtonSpec{}, u).status,
            NewtonResult::Status::Converged);
  const Eigen::VectorXd converged = u;
  const NewtonResult hold = newton.solve({2, 0, 2.0, 1.0}, NewtonSpec{}, u);
  ASSERT_EQ(hold.status, NewtonResult::Status::Converged);
  EXPECT_EQ(hold.iterations, 1);
  EXPECT_LT((u - converged).norm(), 1e-15);
  // End reaction of the prescribed displacement 0.2 over 3 springs: N(d) = d + d^3, d = 0.2/3.
  const double extension = 0.2 / 3;
  EXPECT_NEAR(newton.internalForce()[9], extension + std::pow(extension, 3), 1e-14);
}

// Iteration counts of scalar Newton on g(d) = k (d + a d^3) - F from d = 0, counted as
// documented in newton.hpp (the chain's springs all follow this iteration).
struct ScalarCounts {
  int energy = 0, residual = 0, either = 0, both = 0;
};

ScalarCounts scalarNewtonCounts(double k, double a, double force, const NewtonSpec& spec) {
  ScalarCounts counts;
  double d = 0, firstResidual = 0, firstEnergy = 0;
  int residualAt = 0, energyAt = 0;
  for (int iteration = 1; iteration <= spec.maxIterations; ++iteration) {
    const double residual = std::abs(k * (d + a * d * d * d) - force);
    if (iteration == 1) firstResidual = residual;
    if (!residualAt && iteration > 1 && residual <= spec.residualTolerance * firstResidual) {
      residualAt = iteration;
    }
    if (iteration > 1 && residual <= spec.residualTolerance * firstResidual && energyAt &&
        !counts.both) {
      counts.both = energyAt;
    }
    const double increment = -(k * (d + a * d * d * d) - force) / (k * (1 + 3 * a * d * d));
    const double energy = std::abs(increment * residual);
    if (iteration == 1) firstEnergy = energy;
    d += increment;
    const bool energyMet = energy <= spec.energyTolerance * firstEnergy;
    if (energyMet && !energyAt) energyAt = iteration;
    if (energyMet && iteration > 1 && residual <= spec.residualTolerance * firstResidual &&
        !counts.both) {
      counts.both = iteration;
    }
    if (energyAt && residualAt && counts.both) break;
  }
  counts.energy = energyAt;
  counts.residual = residualAt - 1;
  counts.either = residualAt && residualAt <= energyAt ? residualAt - 1 : energyAt;
  return counts;
}

TEST(Newton, HardeningChainConvergesQuadraticallyToTheClosedFormSolution) {
  const int springs = 4;
  const double k = 1.0, a = 1.0, force = 2.0;  // k (d + a d^3) = F at d = 1
  const double extension = 1.0;
  // Newton's constant for the residual: r_{k+1} ~ C r_k^2, C = |g''| / (2 g'^2) at the root.
  const double slope = k * (1 + 3 * a * extension * extension);
  const double quadraticConstant = 6 * k * a * extension / (2 * slope * slope);
  const double quadraticBound = 10 * quadraticConstant;

  NewtonSpec spec;
  spec.residualTolerance = 1e-8;
  const ScalarCounts expected = scalarNewtonCounts(k, a, force, spec);
  for (auto criterion : {NewtonSpec::Criterion::Energy, NewtonSpec::Criterion::Residual,
                         NewtonSpec::Criterion::Either, NewtonSpec::Criterion::Both}) {
    spec.criterion = criterion;
    SpringChain chain(springs, SpringLaw::cubic(k, a), {}, [&](double t) { return force * t; });
    RecordingObserver observer;
    Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * (springs + 1));
    const NewtonResult result = solveStep(chain, observer, spec, u, 1.0);
    ASSERT_EQ(result.status, NewtonResult::Status::Converged) << result.message;
    const int expectedIterations = criterion == NewtonSpec::Criterion::Energy ? expected.energy
                                   : criterion == NewtonSpec::Criterion::Residual
                                       ? expected.residual
                                   : criterion == NewtonSpec::Criterion::Either ? expected.either
                                                                                : expected.both;
    EXPECT_EQ(result.iterations, expectedIterations) << "criterion " << static_cast<int>(criterion);
    EXPECT_EQ(observer.iterations.size(), static_cast<std::size_t>(result.iterations));
    EXPECT_NEAR(u[3 * springs], springs * extension, 1e-7);
    if (criterion != NewtonSpec::Criterion::Energy) continue;
    EXPECT_NEAR(u[3 * springs], springs * extension, 1e-13);

    // Quadratic convergence over the asymptotic iterations (residual below the initial one,
    // next residual above round-off).
    int measured = 0;
    const auto& records = observer.iterations;
    for (std::size_t i = 1; i + 1 < records.size(); ++i) {
      const double current = records[i].residualNorm, next = records[i + 1].residualNorm;
      if (current >= records[0].residualNorm || next < 1e-12) continue;
      EXPECT_LT(next / (current * current), quadraticBound) << "iteration " << i + 1;
      ++measured;
    }
    EXPECT_GE(measured, 3);
  }
}

// The residual Newton reports for a converged step is that of the state it ended in: the
// iteration records hold the residual before each update, so the last one belongs to the state
// before the final update, orders of magnitude above the final state's (with the energy
// criterion the final residual is often round-off; the residual criterion leaves one to
// compare). The progress line of `covcontact run` showed the last record (e.g. 4.67e-01 for a
// converged augmented re-solve).
TEST(Newton, ReportsTheResidualOfTheStateItConvergedTo) {
  const int springs = 4;
  const double k = 1.0, a = 1.0, force = 2.0;
  SpringChain chain(springs, SpringLaw::cubic(k, a), {}, [&](double t) { return force * t; });
  RecordingObserver observer;
  Newton newton(chain, observer, Newton::Clock::now());
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * (springs + 1));
  NewtonSpec spec;  // the residual criterion leaves a final residual above round-off
  spec.criterion = NewtonSpec::Criterion::Residual;
  spec.residualTolerance = 1e-6;
  const NewtonResult result = newton.solve({1, 0, 1.0, 0.0}, spec, u);
  ASSERT_EQ(result.status, NewtonResult::Status::Converged) << result.message;
  // Independently: the unbalanced force of every free node at the final displacement (the
  // first residual is the end load, the chain starting unstressed).
  Eigen::VectorXd residual(springs);
  for (int node = 1; node <= springs; ++node) {
    residual[node - 1] = newton.internalForce()[3 * node] - (node == springs ? force : 0.0);
  }
  const double expected = residual.norm() / force;
  EXPECT_GT(expected, 1e-13);  // above round-off: the comparison below means something
  EXPECT_LE(expected, spec.residualTolerance);
  EXPECT_NEAR(newton.finalRelativeResidual(), expected, 1e-3 * expected);
  ASSERT_FALSE(observer.iterations.empty());
  EXPECT_LT(newton.finalRelativeResidual(), 1e-3 * observer.iterations.back().relativeResidual);
}

TEST(Newton, LineSearchRescuesFullStepsThatOvershootOnASofteningSpring) {
  // One atan spring loaded by F = atan(0.5), started at d = 5 on the plateau: the full Newton
  // step jumps to d = -18.6 and the iteration runs away; halving the step keeps it near.
  const double force = std::atan(0.5);
  for (bool lineSearch : {false, true}) {
    SpringChain chain(1, SpringLaw::arctangent(), {}, [&](double) { return force; });
    RecordingObserver observer;
    Eigen::VectorXd u = Eigen::VectorXd::Zero(6);
    u[3] = 5.0;
    NewtonSpec spec;
    spec.lineSearch = lineSearch;
    spec.maxIterations = 12;
    const NewtonResult result = solveStep(chain, observer, spec, u, 1.0);
    if (!lineSearch) {
      EXPECT_EQ(result.status, NewtonResult::Status::Failed);
      continue;
    }
    ASSERT_EQ(result.status, NewtonResult::Status::Converged) << result.message;
    EXPECT_NEAR(u[3], 0.5, 1e-12);
  }
}

TEST(Newton, ResidualGrowthBeyondTheDivergenceFactorFails) {
  const double force = std::atan(0.5);
  SpringChain chain(1, SpringLaw::arctangent(), {}, [&](double) { return force; });
  RecordingObserver observer;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(6);
  u[3] = 5.0;
  NewtonSpec spec;
  spec.divergenceFactor = 1.5;  // |atan(-18.6) - F| / |atan(5) - F| = 2.2 at iteration 2
  const NewtonResult result = solveStep(chain, observer, spec, u, 1.0);
  EXPECT_EQ(result.status, NewtonResult::Status::Failed);
  EXPECT_EQ(result.failure, FailureKind::Diverged);
  EXPECT_EQ(result.iterations, 2);
}

// A solve that runs out of iterations names what kept it from converging: the contact points
// that kept switching, as the problem describes them (Model names them by pair, point and mesh
// node; contact_pair_diagnostics.cpp counts them). Nothing is added when none did.
TEST(Newton, AFailedSolveNamesTheContactPointsThatKeptSwitching) {
  for (const std::string& switching :
       {std::string(), std::string("2 contact points kept changing")}) {
    SwitchingChain chain(4, SpringLaw::cubic(1.0, 1.0), {}, [](double t) { return 2.0 * t; });
    chain.switching = switching;
    RecordingObserver observer;
    Eigen::VectorXd u = Eigen::VectorXd::Zero(15);
    NewtonSpec spec;
    spec.maxIterations = 2;  // the hardening chain needs more
    const NewtonResult result = solveStep(chain, observer, spec, u, 1.0);
    ASSERT_EQ(result.status, NewtonResult::Status::Failed);
    EXPECT_EQ(result.message.find("no convergence in 2 iterations"), 0u) << result.message;
    const std::string ending = switching.empty() ? ")" : "); " + switching;
    EXPECT_TRUE(result.message.ends_with(ending)) << result.message;
  }
}

// A spring that softens past its peak force 1 at d = 1 (SpringLaw::peaked), pulled by 1.5:
// there is no equilibrium. Newton goes 0 -> 1.5 -> 0 ... on tangents +1 and -1/2, and
// Newton's word on the failure says that the tangent's determinant changes sign, the mark of a
// fold (tangent_orientation.hpp; the load stepper adds it to the message it gives up with).
TEST(Newton, AFailedSolveOnTangentsOfBothSignsSaysTheResidualFolds) {
  SwitchingChain chain(1, SpringLaw::peaked(), {}, [](double t) { return 1.5 * t; });
  chain.switching = "1 contact point kept changing";
  RecordingObserver observer;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(6);
  NewtonSpec spec;
  spec.maxIterations = 4;  // below the period-2 detector's five norms
  Newton newton(chain, observer, Newton::Clock::now());
  const NewtonResult result = newton.solve({1, 0, 1.0, 0.0}, spec, u);
  ASSERT_EQ(result.status, NewtonResult::Status::Failed);
  ASSERT_EQ(observer.iterations.size(), 4u);
  EXPECT_NEAR(observer.iterations[1].relativeResidual, 0.5, 1e-12);  // at d = 1.5: 1.5 - 0.75
  EXPECT_TRUE(result.message.ends_with("1 contact point kept changing")) << result.message;
  EXPECT_EQ(newton.describeFold().find("the tangent's determinant changes sign between these "
                                       "iterations (1 +, 2 -, 3 +, 4 -)"),
            0u)
      << newton.describeFold();
  // Pulled by 0.5, below the peak, the same spring converges: nothing to describe.
  SwitchingChain below(1, SpringLaw::peaked(), {}, [](double t) { return 0.5 * t; });
  below.switching = chain.switching;
  Newton converging(below, observer, Newton::Clock::now());
  u.setZero();
  ASSERT_EQ(converging.solve({1, 0, 1.0, 0.0}, spec, u).status, NewtonResult::Status::Converged);
  EXPECT_EQ(converging.describeFold(), "");
}

}  // namespace
}  // namespace cc
