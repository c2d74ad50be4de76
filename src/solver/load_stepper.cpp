// Phases of load steps with cut-back and regrowth (see load_stepper.hpp for the time keeping).
#include "solver/load_stepper.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "solver/drive_change.hpp"

namespace cc {

namespace {

// Failures that a retry with the line search, at the same step size, can get through.
// Newton on the non-smooth stick/slip law can cycle between states without any step size
// helping (penalty contact is scale-free in the increment); a line search usually breaks the
// cycle. An element folded by an iterate is likewise more often a full Newton step overshooting
// than a step too large: on the faceted NTS ironing die a slab node crossing a facet edge set
// off state changes whose iterates folded a slab element at every dt down to 1e-10, and the
// line search, which backs off from folded iterates, gets through without a cut-back
// (docs/verification/sliding.md, fifteenth session).
bool lineSearchMayHelp(const NewtonResult& result) {
  return result.status == NewtonResult::Status::Failed &&
         (result.failure == FailureKind::Diverged ||
          result.failure == FailureKind::InvertedElement);
}

// A phase position (in units of its dt) this close to a nominal step end is that step end:
// absorbs the round-off of (t - T) / dt at a restart and of non-dyadic cut-back factors.
constexpr double kPositionSnap = 1e-9;

// The smallest step, in units of the phase's dt: a few times kPositionSnap, below which step
// ends would be snapped back onto a step end already reached.
constexpr double kMinStepFraction = 1e-8;

// Penalty continuation (solveByPenaltyContinuation): tried when a contact penalty exceeds its
// automatic value by more than kContinuationRatio, in solves whose penalties grow by at most
// kContinuationStage. Below 100 the line-search retry got through every stiff block step
// measured; a step that failed there for another reason (maxit=8 on a 9-iteration step at 10
// times, input/stress/cutback_equivalence.deck) is cut back as before.
constexpr double kContinuationRatio = 100;
constexpr double kContinuationStage = 10;

double snapped(double position) {
  const double nearest = std::round(position);
  return std::abs(position - nearest) < kPositionSnap ? nearest : position;
}

// What an attempt of the phase is solved with: the phase's Newton settings, with the
// stabilize_on_failure factor while the step control is stabilising
// (LoadStepper::solveStabilized).
NewtonSpec attemptSpec(const PhaseSpec& phase, bool stabilizing) {
  NewtonSpec spec = phase.newton;
  if (stabilizing) spec.stabilization = phase.newton.stabilizationOnFailure;
  return spec;
}

}  // namespace

// Step size and counters of the phase being run. The StepSize part (the step size, the easy
// steps towards regrowth and the stabilisation on failure) is what the next step, and a restart
// from the last converged one, goes on with. With NewtonSpec::stabilizationOnFailure, a step
// that failed without stabilisation sets `stabilizing`: its cut-backs and the steps after it are
// solved with the factor from their first attempt, until stabilizedEasySteps of them in a row
// (the cut-back regrowth's count) converged easily.
struct LoadStepper::StepControl : StepSize {
  int cutbacks = 0;  // cut-backs of the step being attempted
  int attempts = 0;  // Newton attempts of the step being attempted (cut-backs and retries)
  int convergedInPhase = 0;
  bool singularAtStart = false;  // the last attempt was singular in its first iteration
};

// The state carried from step to step and phase to phase.
struct LoadStepper::PhaseRun {
  Eigen::VectorXd displacement;  // being iterated
  Eigen::VectorXd converged;     // at the last converged step
  double time = 0;               // of the last converged step
  int step = 0;                  // number of the last converged step
  // The last converged step's increment and its dt (NewtonSpec::Predictor::Extrapolate); empty
  // before the first converged step of a run or a restart.
  Eigen::VectorXd lastIncrement;
  double lastDt = 0;
  Eigen::VectorXd predicted;  // the increment predicted for the step being attempted
};

LoadStepper::LoadStepper(NonlinearProblem& problem, StepObserver& observer,
                         std::vector<PhaseSpec> phases, LinearSolverSpec linearSolver,
                         std::vector<TangentDumpRequest> dumps)
    : problem_(problem),
      observer_(observer),
      phases_(std::move(phases)),
      linearSolver_(linearSolver),
      dumps_(std::move(dumps)) {
  // The deck validates these; a violation here is a bug upstream, not a user error.
  for (const PhaseSpec& phase : phases_) {
    const CutbackSpec& cutback = phase.cutback;
    if (!(phase.dt > 0) || phase.steps < 0 || phase.outputEvery < 1 || !(cutback.factor > 0) ||
        !(cutback.factor < 1) || !(cutback.growFactor >= 1) || cutback.maxCutbacks < 0) {
      throw std::invalid_argument("LoadStepper: invalid phase parameters from " +
                                  phase.where.str());
    }
  }
}

LoadStepper::~LoadStepper() = default;

const Eigen::VectorXd* LoadStepper::lastIncrement() const {
  const bool extrapolates = std::any_of(phases_.begin(), phases_.end(), [](const PhaseSpec& phase) {
    return phase.newton.predictor == NewtonSpec::Predictor::Extrapolate;
  });
  if (!extrapolates || !activeRun_ || activeRun_->lastIncrement.size() == 0) return nullptr;
  return &activeRun_->lastIncrement;
}

double LoadStepper::lastDt() const {
  return activeRun_ ? activeRun_->lastDt : 0.0;
}

SolverStatistics LoadStepper::statistics() const {
  SolverStatistics statistics;
  statistics.steps = summary_.stepsConverged;
  statistics.iterations = summary_.totalIterations;
  statistics.cutbacks = summary_.totalCutbacks;
  if (newton_) {
    statistics.assemblies = newton_->assemblies();
    statistics.assemblySeconds = newton_->assemblySeconds();
    statistics.linear = newton_->linearSolver().statistics();
    statistics.choleskyFallbacks = newton_->linearSolver().choleskyFallbacks();
  }
  return statistics;
}

RunSummary LoadStepper::run(const StartState& start) {
  summary_ = RunSummary{};
  newton_ =
      std::make_unique<Newton>(problem_, observer_, Newton::Clock::now(), linearSolver_, dumps_);
  newton_->setTangentCheck(tangentCheck_.first, tangentCheck_.second);
  const Eigen::Index size = 3 * static_cast<Eigen::Index>(problem_.dofMap().numNodes());
  PhaseRun run;
  run.displacement =
      start.displacement.size() == 0 ? Eigen::VectorXd::Zero(size) : start.displacement;
  if (run.displacement.size() != size) {
    throw std::invalid_argument(fmt::format("restart displacement has {} values, the model {}",
                                            run.displacement.size(), size));
  }
  run.converged = run.displacement;
  run.time = start.time;
  run.step = start.step;
  if (start.lastIncrement.size() == size) {
    run.lastIncrement = start.lastIncrement;
    run.lastDt = start.lastDt;
  }
  activeRun_ = &run;
  struct Inactive {
    const PhaseRun*& run;
    ~Inactive() { run = nullptr; }
  } inactiveAfterwards{activeRun_};
  nextStepSize_ = start.stepSize;
  resumeStepSize_ = start.step > 0;
  resumeViscousFactor_ = start.viscousFactor;
  resumeFactorFromStiffness_ = start.viscousFactorFromStiffness;
  summary_.finalTime = start.time;
  double phaseStart = 0;
  for (const PhaseSpec& phase : phases_) {
    if (!runPhase(phase, phaseStart, run)) return summary_;
    phaseStart = phaseStart + phase.steps * phase.dt;
  }
  summary_.outcome = RunSummary::Outcome::Completed;
  return summary_;
}

bool LoadStepper::runPhase(const PhaseSpec& givenPhase, double phaseStart, PhaseRun& run) {
  PhaseSpec phase = givenPhase;  // its viscous factor may be chosen on the way
  StepControl control;
  chosenViscousFactor_ = 0;
  measuredFailureStep_ = 0;
  stiffnessFactorOrigin_.reset();
  double position = std::max(0.0, snapped((run.time - phaseStart) / phase.dt));
  resumePhase(phase, position, control);
  while (position < phase.steps) {
    const double target = snapped(std::min(position + control.fraction, std::floor(position) + 1));
    const double targetTime = phaseStart + target * phase.dt;
    NewtonStep step{run.step + 1, control.attempts++, targetTime, run.time};
    step.predictedIncrement = predictedIncrement(phase, targetTime, run);
    const double dt = (target - position) * phase.dt;
    const NewtonResult result = solveStep(phase, step, dt, control, run);
    if (result.status == NewtonResult::Status::Converged) {
      position = target;
      // Before acceptStep: the restart record written there carries the chosen factor.
      chooseViscousFactor(phase, targetTime, run);
      measureFailureFactor(phase, targetTime, control.stabilizing, run);
      if (!acceptStep(phase, result, targetTime, position >= phase.steps, control, run)) {
        return false;
      }
    } else if (!rejectStep(phase, result, step, dt, control, run)) {
      return false;
    }
  }
  return true;
}

// A restart inside this phase continues with the stored step size, chosen factor and
// stabilisation on failure; at a phase start the phase begins afresh, as it would have.
void LoadStepper::resumePhase(PhaseSpec& phase, double position, StepControl& control) {
  if (!resumeStepSize_ || position >= phase.steps) return;
  resumeStepSize_ = false;
  if (position <= 0) return;
  StepSize resumed = nextStepSize_;
  if (phase.newton.stabilizationOnFailureShare > 0 && resumeViscousFactor_ > 0) {
    phase.newton.stabilizationOnFailure = chosenViscousFactor_ = resumeViscousFactor_;
    if (resumeFactorFromStiffness_) {
      stiffnessFactorOrigin_ = "the stiffness (restart data)";
    }
  }
  // A deck changed for the restart may have dropped stabilize_on_failure from the phase.
  if (!(phase.newton.stabilizationOnFailure > 0)) {
    resumed.stabilizing = false;
    resumed.stabilizedEasySteps = 0;
  }
  static_cast<StepSize&>(control) = resumed;
  if (phase.newton.stabilizationShare > 0 && resumeViscousFactor_ > 0) {
    phase.newton.stabilization = chosenViscousFactor_ = resumeViscousFactor_;
  }
}

NewtonResult LoadStepper::solveStep(PhaseSpec& phase, const NewtonStep& step, double dt,
                                    StepControl& control, PhaseRun& run) {
  NewtonSpec solvedWith = attemptSpec(phase, control.stabilizing);
  NewtonResult result = newton_->solve(step, solvedWith, run.displacement);
  if (lineSearchMayHelp(result) && !phase.newton.lineSearch) {
    // Tried on the same step before the step is cut back (lineSearchMayHelp).
    ++summary_.lineSearchRetries;
    const NewtonStep retry =
        retryStep(step, result, dt, "retrying the step with line search: ", control, run);
    solvedWith.lineSearch = true;
    result = newton_->solve(retry, solvedWith, run.displacement);
  }
  if (continuationMayHelp(result, phase.newton)) {
    // A stiff penalty whose step fails with and without line search fails the same way at every
    // step size (its convergence region shrinks with 1 / eps, not with dt): the step is
    // approached from the automatic penalty before it is cut back.
    ++summary_.continuationRetries;
    const NewtonStep retry =
        retryStep(step, result, dt, "retrying the step by penalty continuation: ", control, run);
    // Its solves without the line-search retry's line search (unless the deck has it): plain
    // Newton ends a period-2 cycle after two periods where the line search runs 30 iterations
    // (block at 1e3 eps_ref: 63 against 108 discarded iterations, fifteenth session).
    result = solveByPenaltyContinuation(attemptSpec(phase, control.stabilizing), retry, run);
  }
  if (result.status == NewtonResult::Status::Failed && !control.stabilizing &&
      !observer_.stopRequested() && failureFactorKnown(phase)) {
    result = solveStabilized(phase, step, result, dt, solvedWith, control, run);
  }
  // The re-solves of augmentStep use the attempt's settings.
  if (result.status == NewtonResult::Status::Converged) {
    result = augmentStep(solvedWith, step, result, run);
  }
  return result;
}

// A step that failed without stabilisation, solved again at the same step size with the phase's
// stabilize_on_failure factor (NewtonSpec::stabilizationOnFailure). It gives the fold of a
// frictional problem (docs/verification/sliding.md) the tangent it lacks there, and only near
// there: the steps before it are the quasi-static problem's. Its cut-backs and the next steps
// keep the factor (control.stabilizing) until grow_after of them in a row converged easily: a
// step that fails without it at one size fails at the smaller ones too (a fold is no matter of
// the step size), and on the ironing die at mu = 0.6 a fold region spans tens of steps, each of
// which would otherwise pay a failed attempt and its line-search retry first.
NewtonResult LoadStepper::solveStabilized(const PhaseSpec& phase, const NewtonStep& step,
                                          const NewtonResult& failed, double dt,
                                          NewtonSpec& solvedWith, StepControl& control,
                                          PhaseRun& run) {
  ++summary_.stabilizedRetries;
  const double factor = phase.newton.stabilizationOnFailure;
  const double share = phase.newton.stabilizationOnFailureShare;
  const std::string origin = measuredFailureStep_ > 0 ? fmt::format("step {}", measuredFailureStep_)
                             : stiffnessFactorOrigin_ ? *stiffnessFactorOrigin_
                                                      : std::string("the restart data");
  const std::string given = share > 0
                                ? fmt::format("stabilize_on_failure_share={:g}: C = {:.4g} from {}",
                                              share, factor, origin)
                                : fmt::format("stabilize_on_failure={:g}", factor);
  const NewtonStep retry = retryStep(
      step, failed, dt, fmt::format("retrying the step with viscous stabilisation ({}): ", given),
      control, run);
  control.stabilizing = true;
  solvedWith = attemptSpec(phase, true);  // the deck's line search, as in the first attempt
  return newton_->solve(retry, solvedWith, run.displacement);
}

// The factor C that makes a step like the one just converged at `time` (not yet booked)
// dissipate `share` of its work (NonlinearProblem::viscousFactorForShare); 0 when that step did
// no work or moved nothing, so that the choice is left to a later step.
double LoadStepper::factorForShare(double share, double time, const PhaseRun& run) const {
  const double factor =
      problem_.viscousFactorForShare(share, time, run.displacement, newton_->internalForce());
  return factor > 0 && std::isfinite(factor) ? factor : 0.0;
}

// The phase's first converged step, solved without stabilisation, measures what a step of the
// phase costs: C = share |W| dt / sum_a m_a |dx_a|^2 makes a step like it dissipate `share` of
// its work W (NewtonSpec::stabilizationShare). A step that did no work leaves the choice to the
// next one.
void LoadStepper::chooseViscousFactor(PhaseSpec& phase, double time, const PhaseRun& run) {
  NewtonSpec& newton = phase.newton;
  if (!(newton.stabilizationShare > 0) || newton.stabilization > 0) return;
  const double factor = factorForShare(newton.stabilizationShare, time, run);
  if (factor == 0) return;
  newton.stabilization = chosenViscousFactor_ = factor;
  observer_.note(fmt::format(
      "viscous stabilisation: factor C = {:.4g} from step {} on (stabilize_share={:.3g}: a step "
      "like step {}, t = {:.6g}, dissipates that share of its work)",
      factor, run.step + 2, newton.stabilizationShare, run.step + 1, time));
}

// After every step converged without stabilisation, the factor a failing step after it is
// stabilised with (NewtonSpec::stabilizationOnFailureShare): C = share |W| dt / sum_a m_a
// |dx_a|^2 makes a step like this one dissipate `share` of its work W, as for
// stabilizationShare. The last quasi-static step before a fold measures the motion the
// stabilisation is to resist there; stabilised steps keep the factor they are solved with.
// A factor from the stiffness (failureFactorKnown) is only a scale, and too large for a body
// whose stiffness as a whole lies far below E L (a thin strip in bending: its viscous forces then
// hold it off the contact meant to carry it). So, until a step converges without stabilisation,
// each stabilised step that dissipated more than `share` of its work lowers it to the factor that
// step measures: C share / s for a step that dissipated s. Never raised: a free body's motion
// dissipates all its work at any C.
void LoadStepper::measureFailureFactor(PhaseSpec& phase, double time, bool stabilizing,
                                       const PhaseRun& run) {
  NewtonSpec& newton = phase.newton;
  if (!(newton.stabilizationOnFailureShare > 0)) return;
  if (stabilizing && !chosenFactorFromStiffness()) return;
  const double factor = factorForShare(newton.stabilizationOnFailureShare, time, run);
  if (factor == 0) return;
  if (stabilizing) {
    if (!(factor < newton.stabilizationOnFailure)) return;
    observer_.note(fmt::format(
        "viscous stabilisation: factor lowered from C = {:.4g} to {:.4g} from step {} on (step {}, "
        "t = {:.6g}, dissipated {:.3g} times the share {:g} of its work)",
        newton.stabilizationOnFailure, factor, run.step + 2, run.step + 1, time,
        newton.stabilizationOnFailure / factor, newton.stabilizationOnFailureShare));
    newton.stabilizationOnFailure = chosenViscousFactor_ = factor;
    stiffnessFactorOrigin_ = fmt::format(
        "step {}, which dissipated more than that share with the factor from the stiffness",
        run.step + 1);
    return;
  }
  newton.stabilizationOnFailure = chosenViscousFactor_ = factor;
  measuredFailureStep_ = run.step + 1;
}

// Whether a failing step has a stabilize_on_failure factor to be solved again with. With
// stabilize_on_failure_share and no step yet converged without stabilisation to measure it from
// (a body that only contact will hold fails the first step), the factor comes from the stiffness
// (NonlinearProblem::viscousFactorForStiffness), at the phase's step size; the first step that
// converges without stabilisation measures it anew.
bool LoadStepper::failureFactorKnown(PhaseSpec& phase) {
  NewtonSpec& newton = phase.newton;
  if (newton.stabilizationOnFailure > 0) return true;
  if (!(newton.stabilizationOnFailureShare > 0)) return false;
  const NonlinearProblem::ViscousFactor chosen =
      problem_.viscousFactorForStiffness(newton.stabilizationOnFailureShare, phase.dt);
  if (!(chosen.factor > 0) || !std::isfinite(chosen.factor)) return false;
  newton.stabilizationOnFailure = chosenViscousFactor_ = chosen.factor;
  stiffnessFactorOrigin_ = chosen.origin + " at dt = " + fmt::format("{:g}", phase.dt) +
                           ", no step having converged without it yet";
  return true;
}

// A failed attempt that is retried on the same step (not cut back): its trial state is
// forgotten, its iterations counted as discarded and the retry logged (with `how` and the
// failure) like a cut-back; returns the retry's step, at the same time and predictor.
NewtonStep LoadStepper::retryStep(const NewtonStep& failed, const NewtonResult& result, double dt,
                                  const std::string& how, StepControl& control, PhaseRun& run) {
  problem_.restoreStep();
  run.displacement = run.converged;
  summary_.discardedIterations += result.iterations;
  observer_.cutback({failed.step, failed.time, dt, how + result.message});
  NewtonStep retry{run.step + 1, control.attempts++, failed.time, run.time};
  retry.predictedIncrement = failed.predictedIncrement;
  return retry;
}

// The extrapolated increment of a step to targetTime: the last converged step's increment times
// the ratio of the step sizes (a constant-velocity predictor), or none: also where a rigid
// surface's motion turns at this step (solver/drive_change.hpp), which the log says.
const Eigen::VectorXd* LoadStepper::predictedIncrement(const PhaseSpec& phase, double targetTime,
                                                       PhaseRun& run) const {
  if (phase.newton.predictor != NewtonSpec::Predictor::Extrapolate || !(run.lastDt > 0) ||
      run.lastIncrement.size() != run.converged.size()) {
    return nullptr;
  }
  if (rigidSurfaceTurns(run.time - run.lastDt, run.time, targetTime)) {
    observer_.note(
        fmt::format("predictor: step {} starts from the converged state, not extrapolated: "
                    "a rigid surface's motion turns at t = {:g}",
                    run.step + 1, run.time));
    return nullptr;
  }
  run.predicted = run.lastIncrement * ((targetTime - run.time) / run.lastDt);
  return &run.predicted;
}

// Whether a rigid surface's translation turns between the steps (before, now] and (now, next].
// Only these: the prescribed displacements are extrapolated with the bodies, and the rest of
// their increment enters the first iteration linearly (K_fp du_p), as the loads enter through
// the residual, so a turn of theirs is corrected to first order; a rigid surface instead stands
// at its new place at the extrapolated iterate (contact_pair.cpp). Measured: the smoothed STS
// and NTS ironing dies take 342 and 365 iterations extrapolating through their press -> drag
// corner and 342 and 368 without (forty-fourth session).
bool LoadStepper::rigidSurfaceTurns(double before, double now, double next) const {
  Eigen::VectorXd offsetsBefore, offsetsNow, offsetsNext;
  problem_.rigidSurfaceOffsets(before, offsetsBefore);
  problem_.rigidSurfaceOffsets(now, offsetsNow);
  problem_.rigidSurfaceOffsets(next, offsetsNext);
  const double stepRatio = (next - now) / (now - before);
  for (Eigen::Index i = 0; i + 2 < offsetsNow.size(); i += 3) {
    if (!driveContinues(offsetsBefore.segment<3>(i), offsetsNow.segment<3>(i),
                        offsetsNext.segment<3>(i), stepRatio)) {
      return true;
    }
  }
  return false;
}

// Whether a failed solve is retried by penalty continuation: it diverged (an element folded by
// an iterate is the line search's case, lineSearchMayHelp), the settings allow it, and a contact
// penalty lies above kContinuationRatio times its automatic value.
bool LoadStepper::continuationMayHelp(const NewtonResult& result, const NewtonSpec& spec) const {
  return result.status == NewtonResult::Status::Failed && result.failure == FailureKind::Diverged &&
         spec.penaltyContinuation && problem_.stiffestPenaltyRatio() > kContinuationRatio;
}

// Penalty continuation, the last retry of a step before a cut-back. Newton's region of quadratic
// convergence shrinks like 1 / eps: a gap error of second order in a displacement correction du
// costs eps |du|^2 / L of force, so at a penalty 1e4 times the automatic one the first iterates of
// a press overshoot and the points at the edge of the contact zone switch open/closed from
// iteration to iteration, at any step size (docs/verification/augmented_lagrangian.md). Solved at
// the automatic penalty first and then at penalties raised by at most kContinuationStage per solve,
// each solve starts a distance of the previous penalty's penetration, O(N / eps), from its
// solution, and that error costs only O(N^2 / (eps L)). Every solve starts from the committed
// history, so the converged step is the deck's penalty problem itself; the iterations of all solves
// count for the step, and their relative norms are measured against the first solve's, as in
// augmentStep. Not the first attempt: below ~1e3 times the automatic penalty plain Newton and its
// line-search retry get through with fewer iterations (measured on the block of
// test_augmented_lagrangian.cpp: 26 + 26 discarded against 56 + 26 at 10 times, 53 + 57 against 220
// + 107 at 1e3).
NewtonResult LoadStepper::solveByPenaltyContinuation(const NewtonSpec& spec, const NewtonStep& step,
                                                     PhaseRun& run) {
  const double ratio = problem_.stiffestPenaltyRatio();
  const int stages = static_cast<int>(std::ceil(std::log(ratio) / std::log(kContinuationStage)));
  NewtonStep stage = step;
  NewtonResult result;
  int iterations = 0;
  struct Restore {  // the deck's penalties again, also when a solve throws (out of memory)
    NonlinearProblem& problem;
    ~Restore() { problem.scalePenalties(1.0); }
  } restore{problem_};
  for (int k = 0; k <= stages; ++k) {
    // Equal factors from 1 / ratio (the automatic penalty) to exactly 1 (the deck's).
    problem_.scalePenalties(k == stages ? 1.0 : std::pow(ratio, double(k - stages) / stages));
    result = newton_->solve(stage, spec, run.displacement);
    iterations += result.iterations;
    result.iterations = iterations;
    if (result.status != NewtonResult::Status::Converged) break;
    stage.predictedIncrement = nullptr;           // the next solve starts from this one's solution
    if (k == 0 && step.referenceResidual == 0) {  // an augmented re-solve keeps its step's
      stage.referenceResidual = newton_->firstResidual();
      stage.referenceEnergy = newton_->firstEnergy();
    }
  }
  return result;
}

// Augmented-Lagrangian contact (Uzawa per step): while the problem updates multipliers, the step
// is solved again at the same time from the displacement it converged to, with its relative
// norms measured against the first solve's (the re-solve starts near equilibrium, and its own
// first residual would set a tolerance below round-off); the iterations of all solves count
// for the step. Without multipliers augment() converges at once and this is a
// no-op. A step that needed the line search keeps it for its re-solves, and a re-solve that
// diverges without it is retried with it from where it started: each update moves the contact
// forces by eps g, and at a stiff penalty the re-solve then cycles as the step's first solve did
// (the small block at 100 eps_ref: a re-solve whose residual grew to 19 times its first value
// threw away the step's converged solves and cut the step back; 11 cut-backs in 5 steps).
// With aug_inner > 0 (NewtonSpec::augmentedInnerTolerance) the re-solves stop early, so that the
// updates interleave with Newton iterations, and a full solve ends the step (the issue's
// Newton-integrated variant; docs/verification/augmented_lagrangian.md).
NewtonResult LoadStepper::augmentStep(NewtonSpec spec, const NewtonStep& step, NewtonResult result,
                                      PhaseRun& run) {
  NewtonStep resolve = step;
  resolve.predictedIncrement = nullptr;  // the re-solve starts from the step's own solution
  resolve.referenceResidual = newton_->firstResidual();
  resolve.referenceEnergy = newton_->firstEnergy();
  bool lastSolveInexact = false;
  for (;;) {
    const NonlinearProblem::Augmentation augmentation = problem_.augment();
    if (!augmentation.note.empty()) observer_.note(augmentation.note);
    using Status = NonlinearProblem::Augmentation::Status;
    if (augmentation.status == Status::Converged && !lastSolveInexact) return result;
    if (augmentation.status == Status::Failed) {
      return {NewtonResult::Status::Failed, result.iterations, FailureKind::Diverged,
              augmentation.message};
    }
    // The rule met at an inexact iterate: the step is solved to the full criterion (the
    // multipliers unchanged) and the rule checked again at that solution.
    lastSolveInexact = augmentation.status == Status::Updated && spec.augmentedInnerTolerance > 0;
    NewtonResult next = resolveAugmented(spec, resolve, lastSolveInexact, run);
    next.iterations += result.iterations;
    if (next.status != NewtonResult::Status::Converged) return next;
    result = next;
  }
}

// One re-solve of augmentStep from the current displacement, with the retries a failed one gets
// (line search, then penalty continuation), each from where the re-solve started (the
// multipliers stay: no restoreStep). `spec` keeps the line search once a retry needed it;
// `inexact` becomes false when continuation solved to the full criterion.
NewtonResult LoadStepper::resolveAugmented(NewtonSpec& spec, const NewtonStep& resolve,
                                           bool& inexact, PhaseRun& run) {
  // aug_inner: an inexact re-solve, measured against its own first residual (the update's
  // disturbance), stops at that fraction of it; its iterate only feeds the next update.
  auto resolveFrom = [&](bool loose) {
    if (!loose) return newton_->solve(resolve, spec, run.displacement);
    NewtonStep inexactResolve = resolve;
    inexactResolve.referenceResidual = inexactResolve.referenceEnergy = 0;
    NewtonSpec inner = spec;  // with the line search if the step has it by now
    inner.criterion = NewtonSpec::Criterion::Residual;
    inner.residualTolerance = spec.augmentedInnerTolerance;
    return newton_->solve(inexactResolve, inner, run.displacement);
  };
  const Eigen::VectorXd start = run.displacement;
  NewtonResult next = resolveFrom(inexact);
  // Counts and logs the failed re-solve and puts the displacement back where it started.
  auto retryFromStart = [&](int& retries, const char* how) {
    ++retries;
    summary_.discardedIterations += next.iterations;
    observer_.note(fmt::format("step {}: retrying the augmented re-solve {}: {}", resolve.step, how,
                               next.message));
    run.displacement = start;
  };
  if (lineSearchMayHelp(next) && !spec.lineSearch) {
    retryFromStart(summary_.lineSearchRetries, "with line search");
    spec.lineSearch = true;
    next = resolveFrom(inexact);
  }
  if (continuationMayHelp(next, spec)) {
    retryFromStart(summary_.continuationRetries, "by penalty continuation");
    inexact = false;  // continuation solves to the full criterion
    next = solveByPenaltyContinuation(spec, resolve, run);
  }
  return next;
}

bool LoadStepper::acceptStep(const PhaseSpec& phase, const NewtonResult& result, double time,
                             bool phaseEnd, StepControl& control, PhaseRun& run) {
  problem_.commitStep();
  run.lastIncrement = run.displacement - run.converged;
  run.lastDt = time - run.time;
  run.converged = run.displacement;
  run.time = time;
  ++run.step;
  ++control.convergedInPhase;
  ++summary_.stepsConverged;
  summary_.totalIterations += result.iterations;
  summary_.finalTime = time;
  const bool write = control.convergedInPhase % phase.outputEvery == 0 || phaseEnd;
  const CutbackSpec& cutback = phase.cutback;
  control.easySteps = result.iterations <= cutback.easyIterations ? control.easySteps + 1 : 0;
  if (control.easySteps >= cutback.growAfter && control.fraction < 1) {
    control.fraction = std::min(1.0, control.fraction * cutback.growFactor);
    control.easySteps = 0;
  }
  if (control.stabilizing) {
    // Past the difficulty, as the regrowth judges it: the next step tries without again.
    control.stabilizedEasySteps =
        result.iterations <= cutback.easyIterations ? control.stabilizedEasySteps + 1 : 0;
    if (control.stabilizedEasySteps >= cutback.growAfter) {
      control.stabilizing = false;
      control.stabilizedEasySteps = 0;
    }
  }
  // At a phase end the next phase starts with a full step, unstabilised.
  nextStepSize_ = phaseEnd ? StepSize{} : static_cast<const StepSize&>(control);
  observer_.convergedResidual(newton_->finalRelativeResidual());
  observer_.stepConverged(run.step, time, result.iterations, control.cutbacks, run.displacement,
                          newton_->internalForce(), write);
  control.cutbacks = 0;
  control.attempts = 0;
  control.singularAtStart = false;
  if (!observer_.stopRequested()) return true;
  summary_.outcome = RunSummary::Outcome::Interrupted;
  // The run's final line names the outcome and the time ("run interrupted at t = ...: ").
  summary_.message = fmt::format("stopped on request after step {}", run.step);
  return false;
}

// The message of the attempt the stepper gives up on, with Newton's word on a fold of the
// residual where it has one (Newton::describeFold): then smaller steps were never the remedy.
// Without that verdict (tangents of one orientation, or signs unknown), contact points that
// kept switching through the last attempt still suggest that no contact pattern the law accepts
// lies near this state: the refined ironing drags stop so, with positive determinants, where
// friction makes a corner of the slab's top side edges (sliding.md, sessions 46 and 48); the
// discrete Coulomb problem is proven unique only below a friction coefficient that falls as the
// mesh is refined (Hild 2002; Hassani et al. 2003). Rounding such an edge removes the cause
// (the refined drags then pass the steps they failed); viscous stabilisation can carry such steps
// (refined twice: at 0.45 % of the work; three times: only at a factor that dissipates about all of
// it). A phase without stabilisation is told both.
std::string LoadStepper::withFold(const std::string& message, const PhaseSpec& phase) const {
  const std::string fold = newton_->describeFold();
  if (!fold.empty()) return message + "; " + fold;
  const NewtonSpec& newton = phase.newton;
  const bool stabilized = newton.stabilization > 0 || newton.stabilizationShare > 0 ||
                          newton.stabilizationOnFailure > 0 ||
                          newton.stabilizationOnFailureShare > 0;
  if (!newton_->endedSwitchingContact() || stabilized) return message;
  return message +
         "; contact points that still switch after every cut-back suggest that no contact "
         "pattern the law accepts lies near this state (with friction, the discrete problem is "
         "proven to have one solution only below a friction coefficient that falls as the mesh "
         "is refined), and smaller steps did not change that; if they sit at a sharp edge of a "
         "body under a tool it sticks to, that edge is a corner of singular pressure, and "
         "modelling it rounded removes the cause (input/README.md, \"Contact pairs\"); else "
         "`newton stabilize_on_failure_share=F`, e.g. 0.01, stabilises only the steps that fail "
         "without it, at a dissipation the run reports (continue from the last converged step "
         "with --restart)";
}

bool LoadStepper::rejectStep(const PhaseSpec& phase, const NewtonResult& result,
                             const NewtonStep& step, double dt, StepControl& control,
                             PhaseRun& run) {
  problem_.restoreStep();
  run.displacement = run.converged;
  summary_.discardedIterations += result.iterations;
  if (result.status == NewtonResult::Status::Interrupted) {
    summary_.outcome = RunSummary::Outcome::Interrupted;
    summary_.message = fmt::format(
        "stopped on request; the unconverged step to t = {:.6g} was discarded", step.time);
    return false;
  }
  // The first iteration's tangent is assembled at the converged state: singular there twice in
  // a row, it will not be cured by smaller steps.
  const bool singularNow = result.failure == FailureKind::SingularSystem && result.iterations == 1;
  const bool persistentSingular = singularNow && control.singularAtStart;
  control.singularAtStart = singularNow;
  control.easySteps = 0;
  if (control.cutbacks >= phase.cutback.maxCutbacks || persistentSingular) {
    summary_.outcome = result.failure == FailureKind::SingularSystem
                           ? RunSummary::Outcome::Singular
                           : RunSummary::Outcome::Diverged;
    summary_.message =
        fmt::format("step {} to t = {:.6g} (dt = {:.3g}) failed after {} cut-backs: {}", step.step,
                    step.time, dt, control.cutbacks, withFold(result.message, phase));
    return false;
  }
  // A step shorter than this (in units of the phase's dt) no longer moves time by more than the
  // round-off the phase positions are snapped with: cutting further would retry the same state
  // at the same time (down to dt = 0 with a large cut-back limit).
  const double nextFraction = control.fraction * phase.cutback.factor;
  const double nextDt = nextFraction * phase.dt;
  if (nextFraction < kMinStepFraction || !(run.time + nextDt > run.time)) {
    summary_.outcome = result.failure == FailureKind::SingularSystem
                           ? RunSummary::Outcome::Singular
                           : RunSummary::Outcome::Diverged;
    summary_.message = fmt::format(
        "step {} to t = {:.6g} (dt = {:.3g}) failed after {} cut-backs, and a further cut-back "
        "to dt = {:.3g} would no longer move time (smallest step: {:g} of the phase's dt): {}",
        step.step, step.time, dt, control.cutbacks, nextDt, kMinStepFraction,
        withFold(result.message, phase));
    return false;
  }
  ++control.cutbacks;
  ++summary_.totalCutbacks;
  control.fraction = nextFraction;
  observer_.cutback({step.step, step.time, control.fraction * phase.dt, result.message});
  return true;
}

}  // namespace cc
