// Newton iteration of one load step: predictor with the prescribed increment, residual and
// energy norms per iteration, convergence tests as documented in newton.hpp, optional line search.
// solve() runs each iteration as named phases over one SolveState (newton_detail), in order.
#include "solver/newton.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <optional>

#include "common/stopwatch.hpp"
#include "solver/newton_stall.hpp"
#include "solver/rigid_body_modes.hpp"
#include "solver/tangent_dump.hpp"

namespace cc {

namespace newton_detail {

// Norms of one iteration relative to the first one of the step. Energies are held in units of
// 2^-energyScale (scaledEnergy) and reported unscaled.
struct Norms {
  double residual = 0, firstResidual = 0, energy = 0, firstEnergy = 0;
  int energyScale = 0;
  double relativeResidual() const { return firstResidual > 0 ? residual / firstResidual : 0; }
  double relativeEnergy() const { return firstEnergy > 0 ? energy / firstEnergy : 0; }
  double unscaledEnergy() const { return std::ldexp(energy, -energyScale); }
};

// An iterative linear solve: the relative residual asked (the forcing term) and the Krylov
// iterations it took.
struct KrylovSolve {
  double tolerance = 0;
  int iterations = 0;
};

// What one call of solve() carries from iteration to iteration.
struct SolveState {
  SolveState(const NewtonStep& solvedStep, const NewtonSpec& solvedSpec)
      : step(solvedStep), spec(solvedSpec) {}
  const NewtonStep& step;
  const NewtonSpec& spec;
  Eigen::VectorXd prescribedTarget;     // the prescribed dofs' values at step.time
  Eigen::VectorXd prescribedIncrement;  // what of it the first iteration carries linearly
  // Nothing drives the step: no load, no prescribed increment (a load that starts later).
  bool undriven = false;
  Norms norms;
  double previousResidual = 0, forcing = kForcingMax;
  KrylovSolve krylov;  // this iteration's iterative solve (zero for a direct one)
  // The sign of this iteration's tangent's determinant, where its factorization told it
  // (TangentSolver::determinantSign): for the fold watch and the iteration's record.
  std::optional<int> determinantSign;
  std::vector<std::uint64_t> activeSets;  // signature of the active set, per iteration
  std::vector<double> residualHistory;    // ||rhs|| per iteration
  std::vector<double> energyHistory;      // |du . rhs| per solved iteration, in norms' unit
  // A plain attempt whose remaining updates go through the line search: it stagnated near
  // convergence (newton_stall.hpp, stagnatesNearConvergence).
  bool damped = false;
  // With an extrapolating predictor: the predicted free increment and K_ff times it (the
  // first norms' floor, setFirstResidual).
  Eigen::VectorXd predictedFree, predictedForce;
};

// The residual of one iterate and the contact changes that led to it.
struct Iterate {
  Eigen::VectorXd rhs;
  ContactChanges changes;
  bool predicted = false;  // the step's extrapolated first iterate
};

}  // namespace newton_detail

namespace {

Eigen::VectorXd gather(const Eigen::VectorXd& nodal, const std::vector<int>& dofs) {
  Eigen::VectorXd values(static_cast<Eigen::Index>(dofs.size()));
  for (std::size_t k = 0; k < dofs.size(); ++k) values[k] = nodal[dofs[k]];
  return values;
}

// ||v||_2 without underflow or overflow of the squares: Eigen's norm() squares the entries, so
// forces of 1e-170 (E = 1e-300) gave a norm of 0 and the first iterate was taken as converged.
// stableNorm() rescales; it is used only outside the range where norm() is exact to round-off,
// so that every ordinary run keeps its norms (and its iteration counts) bit for bit.
double safeNorm(const Eigen::VectorXd& v) {
  const double plain = v.norm();
  if (plain > 1e-140 && plain < 1e140) return plain;
  return v.stableNorm();
}

// |du . rhs| * 2^scale without underflow or overflow of the products (both vectors are scaled by
// powers of two first, which is exact): the energy norms of a step are compared in units of
// 2^-scale, fixed by the first iteration's energy, so the energy test is scale free. For energies
// in the normal range the result is the plain |du . rhs| times an exact power of two, and the
// comparisons energy_k <= tol energy_1 come out exactly as without scaling.
double scaledEnergy(const Eigen::VectorXd& du, const Eigen::VectorXd& rhs, int scale) {
  int duExponent = 0, rhsExponent = 0;
  std::frexp(safeNorm(du), &duExponent);
  std::frexp(safeNorm(rhs), &rhsExponent);
  // ldexp entry by entry: a factor 2^-e itself overflows for a subnormal norm (e < -1022).
  const auto scaled = [](const Eigen::VectorXd& v, int exponent) {
    return v.unaryExpr([exponent](double x) { return std::ldexp(x, -exponent); }).eval();
  };
  const double dot = scaled(du, duExponent).dot(scaled(rhs, rhsExponent));
  return std::ldexp(std::abs(dot), duExponent + rhsExponent + scale);
}

NewtonResult converged(int iterations) {
  return {NewtonResult::Status::Converged, iterations, FailureKind::Diverged, {}};
}

NewtonResult failed(int iteration, FailureKind kind, std::string message) {
  return {NewtonResult::Status::Failed, iteration, kind, std::move(message)};
}

// Stopped on request (SIGINT/SIGTERM), between iterations or within a Krylov solve.
NewtonResult interrupted(int iteration) {
  return {NewtonResult::Status::Interrupted, iteration, FailureKind::Diverged, "interrupted"};
}

bool usesResidual(NewtonSpec::Criterion criterion) {
  return criterion == NewtonSpec::Criterion::Residual || criterion == NewtonSpec::Criterion::Either;
}

// The test after solve k (see newton.hpp); the Residual criterion never converges here.
bool convergedAfterSolve(const NewtonSpec& spec, const newton_detail::Norms& norms, int iteration) {
  const bool energyMet = norms.energy <= spec.energyTolerance * norms.firstEnergy;
  const bool residualMet = iteration > 1 && norms.relativeResidual() <= spec.residualTolerance;
  switch (spec.criterion) {
    case NewtonSpec::Criterion::Energy:
    case NewtonSpec::Criterion::Either:
      return energyMet;
    case NewtonSpec::Criterion::Both:
      return energyMet && residualMet;
    case NewtonSpec::Criterion::Residual:
      return false;
  }
  return false;
}

// A contact active set (every point's state and segment) that comes back after having changed
// is a cycle: Newton on the piecewise smooth contact residual hops between the same few
// stick/slip, open/closed or segment patterns (period 2 and 3 on the ironing cases, issue 14)
// and would go on doing so for all its iterations. Full steps do not leave such a cycle; the
// line search does: the step fails at once and the load stepper retries it with the line search
// (before, the retry came after maxIterations failed iterations). The retry is the same solve as
// before, so its iteration count is too; a step that never revisits a set is untouched.
bool enteredCycle(std::vector<std::uint64_t>& activeSets, const ContactChanges& changes) {
  const bool changed = changes.state > 0 || changes.segment > 0;
  const bool seen = changed && std::find(activeSets.begin(), activeSets.end(), changes.signature) !=
                                   activeSets.end();
  activeSets.push_back(changes.signature);
  return seen;
}

}  // namespace

Newton::Newton(NonlinearProblem& problem, StepObserver& observer, Clock::time_point runStart,
               const LinearSolverSpec& linearSolver, std::vector<TangentDumpRequest> dumps)
    : problem_(problem),
      observer_(observer),
      runStart_(runStart),
      linear_(linearSolver.method),
      dumps_(std::move(dumps)) {
  linear_.setFactorReuse(linearSolver.reuseFactor);
  linear_.setNotifier([this](const std::string& line) { observer_.note(line); });
  // A stop asked for during a long Krylov solve (a million equations: tens of seconds, minutes
  // when it stalls) ends that solve rather than wait for it (SolveInterrupted below).
  linear_.setStopPoll([this] { return observer_.stopRequested(); });
}

void Newton::assembleAt(const Eigen::VectorXd& displacement, const NewtonStep& step,
                        bool withTangent) {
  const Eigen::Matrix3Xd& reference = problem_.referenceCoordinates();
  current_ =
      reference + Eigen::Map<const Eigen::Matrix3Xd>(displacement.data(), 3, reference.cols());
  AssemblyState state;
  state.time = step.time;
  state.previousTime = step.previousTime;
  state.reference = &reference;
  state.current = &current_;
  state.previous = &previous_;
  state.extrapolatedStart = extrapolatedStart_;
  state.viscousFactor = viscousFactor_;
  const auto start = Clock::now();
  ++assemblies_;
  problem_.assemble(state, internalForce_, withTangent ? &tangent_ : nullptr);
  assemblySeconds_ += secondsSince(start);
}

double Newton::stiffnessForceScale() const {
  Eigen::VectorXd diagonal = tangent_.free.diagonal();
  problem_.sumOverProcesses(diagonal);  // each process holds a share of K (several processes)
  const double extent = current_.size() ? current_.cwiseAbs().maxCoeff() : 0.0;
  return (diagonal.size() ? diagonal.cwiseAbs().maxCoeff() : 0.0) * extent;
}

Eigen::VectorXd Newton::freeResidual() const {
  return gather(internalForce_ - externalForce_, problem_.dofMap().freeDofs());
}

// The prescribed dofs at their values of the step's end: after the first iteration, whose
// right-hand side carried their remaining increment linearly (K_fp du_p).
void Newton::applyPrescribed(const Eigen::VectorXd& target, Eigen::VectorXd& displacement) const {
  const DofMap& dofs = problem_.dofMap();
  for (int p = 0; p < dofs.numPrescribed(); ++p) displacement[dofs.prescribedDofs()[p]] = target[p];
}

void Newton::addToFree(Eigen::VectorXd& displacement, const Eigen::VectorXd& du,
                       double scale) const {
  const std::vector<int>& freeDofs = problem_.dofMap().freeDofs();
  for (std::size_t k = 0; k < freeDofs.size(); ++k) displacement[freeDofs[k]] += scale * du[k];
}

double Newton::lineSearch(const NewtonStep& step, const Eigen::VectorXd& du,
                          const Eigen::VectorXd& rhs, Eigen::VectorXd& displacement,
                          double largestResidual) {
  const double initialResidual = rhs.norm();  // ||R(u)||, R = -rhs (linearized in iteration 1)
  double bestFraction = 1, bestResidual = std::numeric_limits<double>::infinity();
  double fraction = 1, lastTried = 1;
  for (int halving = 0; halving <= kLineSearchHalvings; ++halving, fraction *= 0.5) {
    lastTried = fraction;
    Eigen::VectorXd trial = displacement;
    addToFree(trial, du, fraction);
    double residual = std::numeric_limits<double>::infinity();
    try {
      problem_.recallContactSearch();  // R(u + a du) on the segments K was formed on
      assembleAt(trial, step, false);
      residual = freeResidual().norm();
    } catch (const StepFailure&) {
      // an inverted element or a lost projection at this fraction: try a shorter step
    }
    if (!std::isfinite(residual)) residual = std::numeric_limits<double>::infinity();
    if (residual < bestResidual) bestResidual = residual, bestFraction = fraction;
    const double decrease = 1 - kLineSearchDecrease * fraction;
    if (residual <= decrease * initialResidual) break;
    // A trial over master edges that no point has crossed before in this attempt is measured
    // against the attempt's largest residual (newton.hpp, kLineSearchDecrease): this trial,
    // even if an earlier one had a smaller residual.
    if (residual <= decrease * largestResidual) {
      const PendingCrossings crossings = problem_.pendingContactCrossings();
      if (crossings.first > 0 && crossings.repeated == 0) {
        bestFraction = fraction;
        break;
      }
    }
  }
  if (bestFraction != lastTried) {
    // Leave the contributions (and internalForce_) evaluated at the accepted point.
    Eigen::VectorXd accepted = displacement;
    addToFree(accepted, du, bestFraction);
    try {
      problem_.recallContactSearch();
      assembleAt(accepted, step, false);
    } catch (const StepFailure&) {
      // the next iteration's assembly reports it
    }
  }
  return bestFraction;
}

// The assembled tangent K_ff against central differences of the assembled free residual,
// (R(u + h v) - R(u - h v)) / 2h, along the Newton direction and two fixed pseudo-random
// directions, for three step sizes (printed to stderr). An inconsistent tangent shows an error
// independent of h; a non-smooth residual (contact points changing state or segment between
// u - h v and u + h v, counted) an error that does not fall with h. Each line is followed by
// the equations with the largest |K v - fd|: where to look (on the faceted ironing die they
// showed the tangent and the differences on two neighbouring master segments, issue 14).
constexpr int kTangentCheckWorstEquations = 3;
void Newton::checkTangent(const NewtonStep& step, const Eigen::VectorXd& du,
                          const Eigen::VectorXd& displacement) {
  const Eigen::Index n = du.size();
  std::vector<std::pair<std::string, Eigen::VectorXd>> directions{{"newton", du}};
  std::srand(14);  // fixed directions: runs with different tangents see the same ones
  directions.emplace_back("random1", Eigen::VectorXd::Random(n));
  directions.emplace_back("random2", Eigen::VectorXd::Random(n));
  double scale = 1e-3;
  for (int dof : problem_.dofMap().freeDofs()) scale = std::max(scale, std::abs(displacement[dof]));
  (void)problem_.takeContactChanges();
  for (const auto& [name, v] : directions) {
    const Eigen::VectorXd Kv = tangent_.free * v;
    for (const double relative : {1e-4, 1e-6, 1e-8}) {
      const double h = relative * scale / v.cwiseAbs().maxCoeff();
      Eigen::VectorXd plus = displacement, minus = displacement;
      addToFree(plus, v, h);
      addToFree(minus, v, -h);
      problem_.recallContactSearch();
      assembleAt(plus, step, false);
      (void)problem_.takeContactChanges();
      const Eigen::VectorXd rPlus = freeResidual();
      problem_.recallContactSearch();
      assembleAt(minus, step, false);
      const ContactChanges changed = problem_.takeContactChanges();
      const Eigen::VectorXd fd = (rPlus - freeResidual()) / (2 * h);
      fmt::print(stderr,
                 "tangent check: step {} iteration {} direction {} h = {:.1e} |u|: |K v - fd| / "
                 "|fd| = {:.3e} (contact points changing state {} / segment {} between u -+ h v)\n",
                 step.step, tangentCheck_.iteration, name, relative, (Kv - fd).norm() / fd.norm(),
                 changed.state, changed.segment);
      printWorstEquations(Kv, fd);
    }
  }
  problem_.recallContactSearch();
  assembleAt(displacement, step, false);  // the trial state of the iterate again
  (void)problem_.takeContactChanges();
}

void Newton::printWorstEquations(const Eigen::VectorXd& Kv, const Eigen::VectorXd& fd) const {
  const std::vector<int>& freeDofs = problem_.dofMap().freeDofs();
  std::vector<Eigen::Index> order(static_cast<std::size_t>(Kv.size()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  const std::size_t shown = std::min<std::size_t>(kTangentCheckWorstEquations, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(shown), order.end(),
                    [&](Eigen::Index a, Eigen::Index b) {
                      return std::abs(Kv[a] - fd[a]) > std::abs(Kv[b] - fd[b]);
                    });
  for (std::size_t k = 0; k < shown; ++k) {
    const Eigen::Index e = order[k];
    const int dof = freeDofs[static_cast<std::size_t>(e)];
    fmt::print(stderr, "  {} {}: K v - fd = {:.3e} (K v = {:.6e}, fd = {:.6e})\n",
               problem_.nodeLabel(dof / 3), "xyz"[dof % 3], Kv[e] - fd[e], Kv[e], fd[e]);
  }
}

newton_detail::SolveState Newton::beginSolve(const NewtonStep& step, const NewtonSpec& spec,
                                             Eigen::VectorXd& displacement) {
  const DofMap& dofs = problem_.dofMap();
  const Eigen::Matrix3Xd& reference = problem_.referenceCoordinates();
  newton_detail::SolveState s(step, spec);
  viscousFactor_ = spec.stabilization;
  // x_n, the configuration the step starts from. A re-solve of the same attempt (after an
  // augmented-Lagrangian update, a later stage of penalty continuation) starts from an earlier
  // solve's solution instead, and keeps the first solve's x_n: the viscous stabilisation's
  // rate is that of the whole step.
  if (step.step != startedStep_ || step.attempt != startedAttempt_) {
    previous_ =
        reference + Eigen::Map<const Eigen::Matrix3Xd>(displacement.data(), 3, reference.cols());
    startedStep_ = step.step;
    startedAttempt_ = step.attempt;
  }
  s.prescribedTarget.resize(dofs.numPrescribed());
  problem_.prescribedValues(step.time, s.prescribedTarget);
  problem_.externalForces(step.time, externalForce_);
  // Whether anything drives the step is decided on the whole increment, before a predictor
  // takes part of it into the first iterate.
  s.undriven =
      (externalForce_.array() == 0).all() &&
      ((s.prescribedTarget - gather(displacement, dofs.prescribedDofs())).array() == 0).all();
  if (step.predictedIncrement) displacement += *step.predictedIncrement;
  extrapolatedStart_ = step.predictedIncrement != nullptr;
  s.prescribedIncrement = s.prescribedTarget - gather(displacement, dofs.prescribedDofs());
  linear_.beginStep();
  orientation_.begin(spec.maxIterations, !problem_.nodeOwners().empty(),
                     {step.previousTime, step.time, spec.stabilization, spec.lineSearch});
  foldCandidate_ = false;
  return s;
}

std::optional<NewtonResult> Newton::evaluateIterate(newton_detail::SolveState& s, int iteration,
                                                    const Eigen::VectorXd& displacement,
                                                    newton_detail::Iterate& it) {
  it.predicted = extrapolatedStart_;
  try {
    assembleAt(displacement, s.step, true);
    extrapolatedStart_ = false;        // the first iterate's assembly is the only one at the start
    problem_.rememberContactSearch();  // where the line search's trials start their search
    it.changes = problem_.takeContactChanges();
    orientation_.observe(iteration, tangent_.free);
    it.rhs = -freeResidual();
    if (iteration == 1 && problem_.dofMap().numPrescribed() > 0) {
      Eigen::VectorXd prescribedForce = tangent_.coupling * s.prescribedIncrement;
      problem_.sumOverProcesses(prescribedForce);
      it.rhs -= prescribedForce;
    }
  } catch (const StepFailure& failure) {
    return failed(iteration, failure.kind(), failure.what());
  }
  return std::nullopt;
}

// Ends a solve that will not converge as it goes: an active set or residual cycle, or a residual
// that stopped improving (newton_stall.hpp). With the line search none of these apply: it is
// the load stepper's remedy for them. A residual that stops improving near convergence instead
// switches the line search on for the rest of the attempt. Records this iterate's residual
// norm.
std::optional<NewtonResult> Newton::detectStall(newton_detail::SolveState& s, int iteration,
                                                const newton_detail::Iterate& it) {
  const bool lineSearch = s.spec.lineSearch;
  s.norms.residual = safeNorm(it.rhs);
  // An extrapolated first iterate's active set is a prediction (points held closed by their
  // gap history, ContactPair::holdsClosedAtPrediction), not a state Newton passed through: the
  // next iterates returning to it is no cycle.
  if (!lineSearch && !it.predicted && enteredCycle(s.activeSets, it.changes)) {
    if (nearConvergence(s.norms.residual, s.norms.firstResidual)) {
      s.damped = true;  // the rest of this attempt through the line search (newton_stall.hpp)
    } else {
      // The load stepper retries the step with the line search at once (load_stepper.cpp),
      // instead of after maxIterations iterations of the cycle.
      return failed(iteration - 1, FailureKind::Diverged,
                    fmt::format("the contact active set returned at iteration {} to an earlier "
                                "iteration's (a cycle)",
                                iteration));
    }
  }
  s.residualHistory.push_back(s.norms.residual);
  if (!lineSearch && residualCycles(s.residualHistory)) {
    return failed(iteration - 1, FailureKind::Diverged,
                  fmt::format("the residual norms of iterations {} to {} repeat with period 2 "
                              "(a cycle without state changes)",
                              iteration - 3, iteration));
  }
  if (lineSearch || s.damped) return std::nullopt;
  if (stagnatesNearConvergence(s.residualHistory, s.norms.firstResidual)) {
    s.damped = true;  // the rest of this attempt through the line search
    return std::nullopt;
  }
  if (const int best = stoppedImproving(s.residualHistory, s.energyHistory, s.norms.firstResidual);
      best > 0) {
    return failed(iteration - 1, FailureKind::Diverged,
                  fmt::format("the residual has stayed above its value of iteration {} for {} "
                              "iterations, and the energy norm above its lowest (no progress)",
                              best, kNoProgressIterations));
  }
  return std::nullopt;
}

// With an extrapolating predictor the first iterate is already close to the solution, and its
// own residual (about 1e-5 of the step's on example 6.1(a)) would make the relative tests ask
// for round-off: Newton spun 30 iterations there at an absolute residual ten times below the
// one the same step converged to without the predictor. The norms are then measured against
// the step's increment as well: the force K_ff du_pred and energy |du_pred . K_ff du_pred| of
// the predicted free increment through the first tangent, which is what the first residual
// and energy of the step without a predictor are to first order (K_ff du_1 = rhs_1), or the
// predictor's own residual and energy if larger (a poor prediction).
void Newton::setFirstResidual(newton_detail::SolveState& s) {
  const NewtonStep& step = s.step;
  s.norms.firstResidual = step.referenceResidual > 0 ? step.referenceResidual : s.norms.residual;
  if (step.predictedIncrement && step.referenceResidual == 0) {
    s.predictedFree = gather(*step.predictedIncrement, problem_.dofMap().freeDofs());
    s.predictedForce = tangent_.free * s.predictedFree;
    problem_.sumOverProcesses(s.predictedForce);
    s.norms.firstResidual = std::max(s.norms.firstResidual, safeNorm(s.predictedForce));
  }
  firstResidual_ = s.norms.firstResidual;
}

bool Newton::residualAtRoundoff(const newton_detail::SolveState& s, int iteration,
                                bool residualMet) const {
  double forceScale = std::max(safeNorm(internalForce_), safeNorm(externalForce_));
  // A step that nothing drives (no load, no prescribed increment: a load that starts later)
  // has forces that are themselves round-off: the deformation gradient of x = X + u carries
  // errors of eps |x|, which the stiffness turns into forces of eps |K| |x|. Measured against
  // those forces their own round-off was "never reached" and a valid deck diverged.
  if (s.undriven) forceScale = std::max(forceScale, stiffnessForceScale());
  if (s.norms.residual <= kRoundoffResidual * forceScale) return true;
  // A stiff penalty makes forces of eps g whose round-off, eps_N times that of the coordinates,
  // dwarfs the round-off of the internal force itself: at 100 times the automatic penalty the
  // residual stalled at 3e-10 of its first value and Newton spun 30 iterations there. Checked
  // at any relative residual: in the small steps of a cut-back the first residual is small
  // too, and at 1e4 times the automatic penalty the floor lay at 2e-5 of it (a gate at 1e-6
  // failed the step after 10 cut-backs).
  return !residualMet && iteration > 1 &&
         s.norms.residual <= kRoundoffStiffness * stiffnessForceScale();
}

std::optional<NewtonResult> Newton::solveCorrection(newton_detail::SolveState& s, int iteration,
                                                    const Eigen::VectorXd& rhs,
                                                    Eigen::VectorXd& du) {
  const DofMap& dofs = problem_.dofMap();
  try {
    for (const TangentDumpRequest& dump : dumps_) {
      if (dump.step != s.step.step || dump.iteration != iteration ||
          dump.attempt != s.step.attempt) {
        continue;
      }
      writeTangentDump(dump.directory, tangent_, rhs, dofs, current_);
      observer_.note(fmt::format("tangent of step {} attempt {} iteration {} written to {}",
                                 s.step.step, s.step.attempt, iteration, dump.directory));
    }
    linear_.setLayout({dofs.freeDofs(), current_, problem_.nodeOwners()});
    linear_.factorize(tangent_);
    if (linear_.iterative()) {
      if (iteration == 1) {
        s.forcing = s.step.attempt > 0 ? kRetryFirstForcing : kForcingMax;
      } else {
        const double ratio = s.norms.residual / s.previousResidual;
        s.forcing = std::min({kForcingMax, kForcingGamma * ratio * ratio,
                              kForcingResidualFactor * s.norms.relativeResidual()});
        s.forcing = std::max(s.forcing, kForcingMin);
      }
      linear_.setForcing(s.forcing);
    }
    du = linear_.solve(rhs);
    s.determinantSign = linear_.determinantSign();
    orientation_.noteSign(iteration, s.determinantSign);
    s.krylov = linear_.iterative()
                   ? newton_detail::KrylovSolve{s.forcing, linear_.lastSolve().iterations}
                   : newton_detail::KrylovSolve{};
  } catch (const SolveInterrupted&) {
    return interrupted(iteration);
  } catch (const StepFailure& failure) {
    if (failure.kind() != FailureKind::SingularSystem) {
      return failed(iteration, failure.kind(), failure.what());
    }
    orientation_.noteSign(iteration, 0);  // singular: on the fold itself, if it is one
    // Name what is missing (a support, a contact) rather than only the pivot that showed it.
    SingularStiffnessDiagnosis diagnosis = describeSingularStiffness(
        tangent_.free, dofs, current_, problem_.bodies(),
        [this](Eigen::VectorXd& values) { problem_.sumOverProcesses(values); });
    std::string& missing = diagnosis.message;
    if (diagnosis.freeRigidMotion && s.spec.stabilization == 0) {
      missing +=
          "; if contact alone is to hold the body (or will, once it touches), viscous "
          "stabilisation carries it: newton stabilize_on_failure_share=0.01 stabilises the "
          "steps that fail, with a factor the run chooses, newton stabilize=C every step";
    }
    return failed(iteration, failure.kind(), missing + " (" + failure.what() + ")");
  }
  s.previousResidual = s.norms.residual;
  return std::nullopt;
}

void Newton::measureEnergy(newton_detail::SolveState& s, int iteration, const Eigen::VectorXd& du,
                           const Eigen::VectorXd& rhs) {
  newton_detail::Norms& norms = s.norms;
  if (iteration == 1) {
    // The unit of this step's energies: 2^-scale near the first energy (an exact power of two).
    int exponent = 0;
    std::frexp(scaledEnergy(du, rhs, 0), &exponent);
    norms.energyScale = std::clamp(-exponent, -1000, 1000);
    if (std::abs(norms.energyScale) < 900) norms.energyScale = 0;  // normal range: no scaling
  }
  norms.energy = scaledEnergy(du, rhs, norms.energyScale);
  s.energyHistory.push_back(norms.energy);
  if (iteration == 1) {
    // A reference energy from an earlier solve of this step is in unscaled units: used only
    // when this one is unscaled too.
    norms.firstEnergy = s.step.referenceEnergy > 0 && norms.energyScale == 0
                            ? s.step.referenceEnergy
                            : norms.energy;
    if (s.predictedForce.size() > 0) {
      norms.firstEnergy = std::max(
          norms.firstEnergy, scaledEnergy(s.predictedFree, s.predictedForce, norms.energyScale));
    }
    firstEnergy_ = norms.firstEnergy;
  }
}

// Evaluate once more at the converged displacement, so that the internal force (the reactions)
// and every contribution's trial state (the contact history to be committed) belong to the
// state the step ends in, not to the one before the last update.
NewtonResult Newton::finishConverged(const newton_detail::SolveState& s,
                                     const Eigen::VectorXd& displacement, int iteration) {
  try {
    assembleAt(displacement, s.step, false);
  } catch (const StepFailure& failure) {
    return failed(iteration, failure.kind(), failure.what());
  }
  finalRelativeResidual_ =
      s.norms.firstResidual > 0 ? safeNorm(freeResidual()) / s.norms.firstResidual : 0.0;
  return converged(iteration);
}

NewtonResult Newton::solve(const NewtonStep& step, const NewtonSpec& spec,
                           Eigen::VectorXd& displacement) {
  newton_detail::SolveState s = beginSolve(step, spec, displacement);
  newton_detail::Norms& norms = s.norms;
  for (int iteration = 1; iteration <= spec.maxIterations; ++iteration) {
    newton_detail::Iterate it;
    if (auto stop = evaluateIterate(s, iteration, displacement, it)) return *stop;
    if (auto stop = detectStall(s, iteration, it)) return *stop;
    if (iteration == 1) setFirstResidual(s);
    if (!std::isfinite(norms.residual)) {
      return failed(iteration, FailureKind::NotFinite, "residual is not finite");
    }
    const bool residualMet = iteration > 1 && norms.relativeResidual() <= spec.residualTolerance;
    const bool atRoundoff = residualAtRoundoff(s, iteration, residualMet);
    if (iteration > 1 && usesResidual(spec.criterion) && (residualMet || atRoundoff)) {
      finalRelativeResidual_ = norms.relativeResidual();
      return converged(iteration - 1);
    }
    if (iteration > 1 && norms.relativeResidual() > spec.divergenceFactor) {
      return failed(iteration, FailureKind::Diverged,
                    fmt::format("residual grew to {:.3g} times its first value at iteration {}",
                                norms.relativeResidual(), iteration));
    }
    Eigen::VectorXd du;
    if (auto stop = solveCorrection(s, iteration, it.rhs, du)) return *stop;
    if (tangentCheck_.step == step.step && tangentCheck_.iteration == iteration) {
      checkTangent(step, du, displacement);
    }
    measureEnergy(s, iteration, du, it.rhs);
    if (iteration == 1) applyPrescribed(s.prescribedTarget, displacement);
    const bool searched = spec.lineSearch || s.damped;
    const double fraction =
        searched ? lineSearch(step, du, it.rhs, displacement,
                              *std::max_element(s.residualHistory.begin(), s.residualHistory.end()))
                 : 1.0;
    addToFree(displacement, du, fraction);

    observer_.iteration({step.step, step.attempt, iteration, step.time, norms.residual,
                         norms.relativeResidual(), norms.unscaledEnergy(), norms.relativeEnergy(),
                         secondsSince(runStart_), it.changes, s.krylov.tolerance,
                         s.krylov.iterations, searched ? fraction : 0.0, s.determinantSign});
    if (atRoundoff || convergedAfterSolve(spec, norms, iteration)) {
      return finishConverged(s, displacement, iteration);
    }
    if (observer_.stopRequested()) return interrupted(iteration);
  }
  const std::string switching = problem_.describeSwitchingContact();
  foldCandidate_ = !switching.empty();
  return failed(spec.maxIterations, FailureKind::Diverged,
                fmt::format("no convergence in {} iterations (relative residual {:.3g}, relative "
                            "energy {:.3g}){}",
                            spec.maxIterations, norms.relativeResidual(), norms.relativeEnergy(),
                            switching.empty() ? "" : "; " + switching));
}

std::string Newton::describeFold() const {
  return foldCandidate_ ? orientation_.describe() : std::string();
}

}  // namespace cc
