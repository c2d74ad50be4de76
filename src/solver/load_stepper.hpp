// Load stepping in phases with Newton's method per step and automatic cut-back: halve the step
// on divergence, NaN/Inf, an element or contact failure or too many iterations; regrow after
// easy steps; stop (keeping every converged step) after the cut-back limit.
#pragma once

#include <string>
#include <vector>

#include "deck/problem_spec.hpp"
#include "solver/nonlinear_problem.hpp"

namespace cc {

struct RunSummary {
  enum class Outcome { Completed, Diverged, Interrupted, Singular };
  Outcome outcome = Outcome::Completed;
  int stepsConverged = 0;
  int totalIterations = 0;
  int totalCutbacks = 0;
  double finalTime = 0;
  std::string message;  // why the run stopped, if it did not complete
};

// Where a run starts: t = 0 and zero displacement, or a restart from a stored step.
struct StartState {
  int step = 0;
  double time = 0;
  Eigen::VectorXd displacement;  // 3 * numNodes; empty = zero
};

class LoadStepper {
 public:
  LoadStepper(NonlinearProblem& problem, StepObserver& observer, std::vector<PhaseSpec> phases);
  RunSummary run(const StartState& start = {});

 private:
  NonlinearProblem& problem_;
  StepObserver& observer_;
  std::vector<PhaseSpec> phases_;
};

}  // namespace cc
