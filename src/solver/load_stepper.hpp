// Load stepping in phases with Newton's method per step and automatic cut-back: halve the step
// on divergence, NaN/Inf, an element or contact failure or too many iterations; regrow after
// easy steps; stop (keeping every converged step) after the cut-back limit.
//
// Time: phases run back to back from t = 0; phase i ends at T_i + steps_i * dt_i. Within a
// phase the position is kept in units of its dt (s = 0..steps), so step ends are computed as
// T_i + s * dt without accumulating increments. A (cut-back) step never crosses the next
// nominal step end floor(s) + 1, so every nominal time of the phase, and its end, is hit exactly.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "solver/newton.hpp"
#include "solver/nonlinear_problem.hpp"
#include "spec/problem_spec.hpp"

namespace cc {

struct RunSummary {
  enum class Outcome { Completed, Diverged, Interrupted, Singular };
  Outcome outcome = Outcome::Completed;
  int stepsConverged = 0;
  int totalIterations = 0;
  int totalCutbacks = 0;
  // Steps whose plain Newton failed and that were retried with line search, and the iterations
  // of every failed attempt (retried or cut back): work done that is not in totalIterations.
  int lineSearchRetries = 0;
  int discardedIterations = 0;
  // Steps of a stiff penalty retried by penalty continuation after their line-search retry
  // failed (load_stepper.cpp).
  int continuationRetries = 0;
  // Steps retried with viscous stabilisation after failing without it
  // (NewtonSpec::stabilizationOnFailure).
  int stabilizedRetries = 0;
  double finalTime = 0;
  std::string message;  // why the run stopped, if it did not complete
};

// The automatic step size: the next step in units of its phase's dt, and the consecutive easy
// steps counted towards regrowth; with NewtonSpec::stabilizationOnFailure, whether the next
// step starts stabilised and the easy steps counted towards leaving the stabilisation.
struct StepSize {
  double fraction = 1;
  int easySteps = 0;
  bool stabilizing = false;
  int stabilizedEasySteps = 0;
};

// Where a run starts: t = 0 and zero displacement, or a restart from a stored step (with the
// step size the interrupted run would have used next, so that it continues identically).
struct StartState {
  int step = 0;
  double time = 0;
  Eigen::VectorXd displacement;  // 3 * numNodes; empty = zero
  StepSize stepSize;
  // The increment and dt of the step started from (LoadStepper::lastIncrement); empty: the
  // first step is not extrapolated.
  Eigen::VectorXd lastIncrement;
  double lastDt = 0;
  // The factor the phase started from chose (NewtonSpec::stabilizationShare; 0: none yet).
  double viscousFactor = 0;
  bool viscousFactorFromStiffness = false;  // and whether it came from the stiffness
};

class LoadStepper {
 public:
  LoadStepper(NonlinearProblem& problem, StepObserver& observer, std::vector<PhaseSpec> phases,
              LinearSolverSpec linearSolver = {}, std::vector<TangentDumpRequest> dumps = {});
  ~LoadStepper();
  RunSummary run(const StartState& start = {});
  // Work so far (also during run(), e.g. from the observer for a progress line).
  SolverStatistics statistics() const;
  // The step size of the next step; during StepObserver::stepConverged, the one that follows
  // the converged step (what a restart from that step needs).
  StepSize nextStepSize() const { return nextStepSize_; }
  // During StepObserver::stepConverged, the converged step's increment and dt if a phase
  // extrapolates (NewtonSpec::Predictor::Extrapolate), what a restart needs; otherwise null.
  const Eigen::VectorXd* lastIncrement() const;
  double lastDt() const;
  // During StepObserver::stepConverged, the viscous stabilisation factor the running phase
  // chose for the steps after it (NewtonSpec::stabilizationShare; with
  // stabilizationOnFailureShare, the factor for the next failing step; 0: none chosen).
  double chosenViscousFactor() const { return chosenViscousFactor_; }
  // Whether that factor came from the stiffness and stabilised steps may still lower it
  // (stabilize_on_failure_share before any step converged without stabilisation).
  bool chosenFactorFromStiffness() const {
    return measuredFailureStep_ == 0 && stiffnessFactorOrigin_.has_value();
  }
  // Diagnostics: see Newton::setTangentCheck.
  void setTangentCheck(int step, int iteration) { tangentCheck_ = {step, iteration}; }

 private:
  struct PhaseRun;
  struct StepControl;
  // NewtonSpec::Predictor::Extrapolate: the increment of the step to targetTime (null: none).
  const Eigen::VectorXd* predictedIncrement(const PhaseSpec& phase, double targetTime,
                                            PhaseRun& run) const;
  bool rigidSurfaceTurns(double before, double now, double next) const;
  // Prepares the retry of a failed attempt on the same step (load_stepper.cpp).
  NewtonStep retryStep(const NewtonStep& failed, const NewtonResult& result, double dt,
                       const std::string& how, StepControl& control, PhaseRun& run);
  // A step solved at contact penalties growing from the automatic ones to the deck's
  // (load_stepper.cpp): the retry of a stiff penalty's failed step before it is cut back.
  NewtonResult solveByPenaltyContinuation(const NewtonSpec& spec, const NewtonStep& step,
                                          PhaseRun& run);
  bool continuationMayHelp(const NewtonResult& result, const NewtonSpec& spec) const;
  // Re-solves a converged step while the problem updates contact multipliers.
  NewtonResult augmentStep(NewtonSpec spec, const NewtonStep& step, NewtonResult result,
                           PhaseRun& run);
  // One of its re-solves, with its retries (load_stepper.cpp).
  NewtonResult resolveAugmented(NewtonSpec& spec, const NewtonStep& resolve, bool& inexact,
                                PhaseRun& run);
  // Each returns false when the run stops (summary_ says why).
  bool runPhase(const PhaseSpec& givenPhase, double phaseStart, PhaseRun& run);
  // A restart inside the phase: the stored step size, chosen factor and stabilisation on failure.
  void resumePhase(PhaseSpec& phase, double position, StepControl& control);
  // One attempt at a step of size dt and the retries a failed one gets before it is cut back
  // (line search, penalty continuation, stabilisation); a converged one is augmented with the
  // Newton settings the last retry left.
  NewtonResult solveStep(PhaseSpec& phase, const NewtonStep& step, double dt, StepControl& control,
                         PhaseRun& run);
  // NewtonSpec::stabilizationOnFailure: the failed step again, stabilised (load_stepper.cpp).
  NewtonResult solveStabilized(const PhaseSpec& phase, const NewtonStep& step,
                               const NewtonResult& failed, double dt, NewtonSpec& solvedWith,
                               StepControl& control, PhaseRun& run);
  // The viscous factor for `share` of the step just converged (0: none to be had).
  double factorForShare(double share, double time, const PhaseRun& run) const;
  // NewtonSpec::stabilizationShare: sets the phase's factor from its first converged step.
  void chooseViscousFactor(PhaseSpec& phase, double time, const PhaseRun& run);
  // NewtonSpec::stabilizationOnFailureShare: sets the phase's stabilize_on_failure factor from
  // each step that converged without stabilisation, and lowers a factor from the stiffness after
  // a stabilised step that dissipated more than the share.
  void measureFailureFactor(PhaseSpec& phase, double time, bool stabilizing, const PhaseRun& run);
  // Whether a failed step can be solved again stabilised; sets the stabilize_on_failure_share
  // factor from the stiffness when no step has measured it yet.
  bool failureFactorKnown(PhaseSpec& phase);
  bool acceptStep(const PhaseSpec& phase, const NewtonResult& result, double time, bool phaseEnd,
                  StepControl& control, PhaseRun& run);
  std::string withFold(const std::string& message, const PhaseSpec& phase) const;
  bool rejectStep(const PhaseSpec& phase, const NewtonResult& result, const NewtonStep& step,
                  double dt, StepControl& control, PhaseRun& run);

  NonlinearProblem& problem_;
  StepObserver& observer_;
  std::vector<PhaseSpec> phases_;
  LinearSolverSpec linearSolver_;
  std::vector<TangentDumpRequest> dumps_;
  std::unique_ptr<Newton> newton_;
  RunSummary summary_;
  StepSize nextStepSize_;
  bool resumeStepSize_ = false;             // a restart's step size still waits for its phase
  double resumeViscousFactor_ = 0;          // a restart's chosen factor, for the same phase
  bool resumeFactorFromStiffness_ = false;  // and whether it came from the stiffness
  double chosenViscousFactor_ = 0;
  int measuredFailureStep_ = 0;  // the step measureFailureFactor last measured
  // Set when the failure factor came from the stiffness: how (for the run's messages).
  std::optional<std::string> stiffnessFactorOrigin_;
  std::pair<int, int> tangentCheck_{-1, -1};
  const PhaseRun* activeRun_ = nullptr;  // during run()
};

}  // namespace cc
