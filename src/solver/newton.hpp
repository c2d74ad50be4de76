// Newton's method for one load step, FEAP style: the first iteration carries the prescribed
// displacement increment as a linear predictor (K_fp du_p on the right-hand side), every
// iteration logs the residual and energy norms, convergence follows NewtonSpec::criterion.
// With NewtonStep::predictedIncrement (deck: predictor=extrapolate) the first iterate is the
// converged state plus that increment, only the rest of the prescribed increment enters
// linearly, and the first norms are at least those of the predicted increment (newton.cpp).
//
// Iterations per step = number of linear solves (FEAP's count of TANG,,1 cycles):
//  - Energy: after solve k, |du_k . rhs_k| <= energyTolerance |du_1 . rhs_1| -> k iterations.
//    A linear problem therefore takes 2 (the second solve confirms), exactly as in FEAP.
//  - Residual: at the start of iteration k >= 2, ||rhs_k|| <= residualTolerance ||rhs_1|| ->
//    k - 1 iterations (no solve is needed to see it). A linear problem takes 1.
//  - Either: whichever of the two tests above passes first.
//  - Both: after solve k, the energy test and ||rhs_k|| <= residualTolerance ||rhs_1|| (both of
//    iteration k) -> k iterations.
//  - Round-off: a residual at round-off level of the forces (||rhs_k|| <= kRoundoffResidual *
//    max(||f_int||, ||f_ext||)) cannot be reduced further, whatever the relative tests say. In a
//    step that no load and no prescribed increment drives, the forces are themselves round-off;
//    the scale then also includes max|K_ff,ii| max|x| (the force of a coordinate error eps|x|).
//  - Norms are scale free: computed without underflow (E = 1e-300 gave ||rhs|| = 0 and the first
//    iterate passed as converged), energies compared in units fixed by the first iteration.
//    Residual and Either then converge at the start of iteration k >= 2 (k - 1 iterations);
//    otherwise solve k is still done and logged, as FEAP would, and the step converges after
//    it (k iterations). A step that starts in equilibrium therefore takes 1 iteration.
// rhs_1 = -(R_f + K_fp du_p), rhs_k = -R_f for k >= 2, R = f_int - f_ext.
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "solver/nonlinear_problem.hpp"
#include "solver/tangent_orientation.hpp"
#include "solver/tangent_solver.hpp"
#include "spec/problem_spec.hpp"

namespace cc {

namespace newton_detail {
struct SolveState;  // what one solve carries from iteration to iteration (newton.cpp)
struct Iterate;     // the residual of one iterate and the contact changes that led to it
}  // namespace newton_detail

// ||rhs|| below this multiple of max(||f_int||, ||f_ext||) is round-off of the assembled sums
// (machine epsilon times the growth of summing many element contributions per dof).
inline constexpr double kRoundoffResidual = 1e3 * 2.220446049250313e-16;
// ||rhs|| below this multiple of max|K_ii| max|x| is round-off too: a force computed from
// coordinates x carries errors of machine epsilon |x| times the stiffness that makes it (a
// lower bound: each dof sums several such terms).
inline constexpr double kRoundoffStiffness = 10 * 2.220446049250313e-16;

// Line search (NewtonSpec::lineSearch): backtracking with the Armijo test on the residual norm,
// the merit function that suits a tangent that is neither symmetric nor smooth (frictional
// slip). Accept the step fraction s when ||R_f(u + s du)|| <= (1 - kLineSearchDecrease s)
// ||rhs||, halving s at most kLineSearchHalvings times, else take the tried fraction with the
// smallest ||R_f||. An energy test |du . R_f(u + s du)| <= 0.8 |du . rhs| was used before: it
// accepts full steps whose residual is orthogonal to du, and Newton then cycled between
// stick/slip patterns (or stagnated) for eps_T above ~1e2 E/h on example 6.1, whatever the step
// size. Halving down to 2^-10 is needed there for eps = 1e5 E/h (measured; 2^-4 was not
// enough). In the first iteration the prescribed dofs sit at their new values in every trial;
// ||rhs|| then is the linearized residual at s = 0. Each trial costs one residual assembly.
// A trial that puts contact points on other master segments, none of which has changed segment
// before in this attempt, is measured against the attempt's largest ||rhs|| instead (a
// non-monotone test, after Grippo, Lampariello & Lucidi 1986). Where the master's normal jumps
// at an edge (a faceted master) the residual jumps as a point crosses, by a fraction of its
// force that no shorter step removes: the monotone test let the iterates creep up to the edge
// and stop there. With line_search=yes the faceted ironing die (ironing_sts_mu03_wide) stopped
// at t = 0.40 after 28 cut-backs, its iterates at a relative residual of 5e-7 for 30 iterations;
// now it completes without a cut-back, at the converged states of the run without the line
// search (docs/verification/sliding.md). A point crossing again (back over an edge: a hop) is
// still measured monotonically: there the backtracking damps the hop, which the line-search
// retries of the ball decks rely on (measured: taking all crossings non-monotonically cost two
// of them a cut-back). Stick/slip and open/closed changes keep the residual continuous.
inline constexpr double kLineSearchDecrease = 1e-4;
inline constexpr int kLineSearchHalvings = 10;

// Inexact Newton (iterative linear solves): the forcing term eta_k, the relative residual the
// Krylov solve of iteration k must reach, follows Eisenstat & Walker's choice 2 (1996),
// eta_k = kForcingGamma (||R_k|| / ||R_{k-1}||)^2, and is never above kForcingResidualFactor
// times the relative residual ||R_k|| / ||R_1|| of the step, so that it tightens as Newton
// converges: eta_k = O(||R_k||) keeps the quadratic rate (Dembo, Eisenstat & Steihaug 1982),
// and the last solves stay accurate enough for the energy criterion (1e-16). Bounded to
// [kForcingMin, kForcingMax]; the first iteration of a step uses kForcingMax.
inline constexpr double kForcingGamma = 0.9;
// The factor was 1 until the thirty-second session. Where contact points change state over
// many iterations Newton converges linearly (||R_k|| / ||R_{k-1}|| ~ 0.5), and the bound then
// asked 1e-5 .. 1e-7 of solves whose Newton step the next state change overtakes anyway. With
// 100 (measured, docs/performance/solvers.md): the bulk 79 k die on 2 processes took 589
// instead of 797 Krylov iterations with the same Newton iterations per step and every
// iteration's energy within 12 % of the factor-1 run's (1000: 527 its, 17 %; no bound: 424 its,
// but energies off by 3x, which the convergence test must not see); the thin 20 k and 125 k
// decks one Newton iteration fewer in all, the 20 k one now within +1 per step of MUMPS's
// (tests/regression/parallel: --case inexact).
inline constexpr double kForcingResidualFactor = 100;
inline constexpr double kForcingMax = 1e-3;
inline constexpr double kForcingMin = 1e-12;
// The first solve of an attempt after a failed one (a retry or a cut-back) is asked for
// kRetryFirstForcing instead of kForcingMax. The first iteration carries the step's load and
// prescribed motion, and where contact closes in the step the active set Newton starts from
// depends on how exactly it is solved. The ironing case of issue 14 refined three times (108 k
// equations, `solver=auto`: GMRES + BoomerAMG) stalled in its first step at 2e-7 of the first
// residual for 30 iterations, with 20-40 points changing state and up to 360 changing segment
// in each; its line-search retry took the same path and stalled again. Every later solve made
// exact (1e-12, some by UMFPACK) still stalled: the first solve at 1e-3 had set the path. Asked
// for 1e-5 or 1e-8, the first solve put Newton on the direct solver's path (MUMPS: converged in
// 10 iterations). Only for retries: at every first solve 1e-5 cost 5-7 % more Krylov
// iterations and CPU time on the bulk 79 k die and the thin 57 k deck, which never failed
// (docs/verification/sliding.md, forty-first session).
inline constexpr double kRetryFirstForcing = 1e-5;

// `covcontact run --dump-tangent STEP:ITER[:ATTEMPT]`: the system of that Newton iteration is
// written (solver/tangent_dump.hpp) to `directory` before it is solved. ATTEMPT counts the
// step's earlier attempts (NewtonStep::attempt: 0 the first, 1 the line-search retry or first
// cut-back after it, ...), so that the stalled retry of a step can be dumped too.
struct TangentDumpRequest {
  int step = 0;       // 0 = none
  int iteration = 0;  // 1-based
  int attempt = 0;    // NewtonStep::attempt
  std::string directory;
};

struct NewtonStep {
  int step = 0;             // number the step gets if it converges (1-based)
  int attempt = 0;          // earlier attempts of this step (cut-backs, line-search retries)
  double time = 0;          // t_{n+1}
  double previousTime = 0;  // t_n
  // Augmented-Lagrangian re-solves of a converged step: the first residual and energy norms of
  // the step's first solve, against which this solve's relative norms are measured (0: its
  // own first iteration, as for every ordinary step).
  double referenceResidual = 0;
  double referenceEnergy = 0;
  // NewtonSpec::Predictor::Extrapolate: added to every dof (3 * numNodes) of the converged state
  // before the first iteration; the prescribed values' remaining increment enters linearly.
  // Null: the first iterate is the converged state.
  const Eigen::VectorXd* predictedIncrement = nullptr;
};

struct NewtonResult {
  enum class Status { Converged, Failed, Interrupted };
  Status status = Status::Failed;
  int iterations = 0;  // converged: see the definition above; failed: iteration reached
  FailureKind failure = FailureKind::Diverged;
  std::string message;  // why it failed
};

// Work counters of a run (benchmarks, progress line).
struct SolverStatistics {
  int steps = 0;
  int iterations = 0;
  int cutbacks = 0;
  int assemblies = 0;  // calls of NonlinearProblem::assemble (tangent and residual-only)
  double assemblySeconds = 0;
  int choleskyFallbacks = 0;
  LinearSolverStatistics linear;
};

class Newton {
 public:
  using Clock = std::chrono::steady_clock;
  Newton(NonlinearProblem& problem, StepObserver& observer, Clock::time_point runStart,
         const LinearSolverSpec& linearSolver = {}, std::vector<TangentDumpRequest> dumps = {});

  // `displacement` (3 * numNodes) holds the converged state at step.previousTime on entry and
  // the solution at step.time when converged; otherwise it is left in between (the caller
  // restores it and calls problem.restoreStep()).
  NewtonResult solve(const NewtonStep& step, const NewtonSpec& spec, Eigen::VectorXd& displacement);

  // Internal force of the last assembly. A converged step always ends with an assembly (force
  // only) at its final displacement, so this is the internal force of the converged state.
  const Eigen::VectorXd& internalForce() const { return internalForce_; }
  // The first residual and energy norms of the last solve (what its relative norms divide by).
  double firstResidual() const { return firstResidual_; }
  // |R|/|R0| at the state the last converged solve ended in (after its last update; the
  // iteration records give the residual before each update).
  double finalRelativeResidual() const { return finalRelativeResidual_; }
  double firstEnergy() const { return firstEnergy_; }
  int assemblies() const { return assemblies_; }
  double assemblySeconds() const { return assemblySeconds_; }
  const TangentSolver& linearSolver() const { return linear_; }
  // After a solve that ran out of iterations with contact points switching: whether the
  // tangents of its last iterations have determinants of both signs, as a sentence for the
  // message (tangent_orientation.hpp), else empty. Costs a factorization per kept tangent, so
  // the load stepper asks only when it gives up.
  std::string describeFold() const;
  // Whether the last solve ran out of iterations with contact points switching (state or
  // segment) at least three times each (Model::describeSwitchingContact).
  bool endedSwitchingContact() const { return foldCandidate_; }
  // Diagnostics (covcontact run --check-tangent): at this step and iteration, compare the
  // assembled tangent with central differences of the residual (printed to stderr).
  void setTangentCheck(int step, int iteration) { tangentCheck_ = {step, iteration}; }

 private:
  // The phases of solve(), in the order one iteration runs them. Those returning a result end
  // the solve with it (a failure, an interruption); none means the iteration goes on.
  newton_detail::SolveState beginSolve(const NewtonStep& step, const NewtonSpec& spec,
                                       Eigen::VectorXd& displacement);
  std::optional<NewtonResult> evaluateIterate(newton_detail::SolveState& s, int iteration,
                                              const Eigen::VectorXd& displacement,
                                              newton_detail::Iterate& it);
  std::optional<NewtonResult> detectStall(newton_detail::SolveState& s, int iteration,
                                          const newton_detail::Iterate& it);
  void setFirstResidual(newton_detail::SolveState& s);
  // Whether ||rhs|| is at round-off of the forces (see "Round-off" above).
  bool residualAtRoundoff(const newton_detail::SolveState& s, int iteration,
                          bool residualMet) const;
  std::optional<NewtonResult> solveCorrection(newton_detail::SolveState& s, int iteration,
                                              const Eigen::VectorXd& rhs, Eigen::VectorXd& du);
  void measureEnergy(newton_detail::SolveState& s, int iteration, const Eigen::VectorXd& du,
                     const Eigen::VectorXd& rhs);
  void applyPrescribed(const Eigen::VectorXd& target, Eigen::VectorXd& displacement) const;
  NewtonResult finishConverged(const newton_detail::SolveState& s,
                               const Eigen::VectorXd& displacement, int iteration);

  void assembleAt(const Eigen::VectorXd& displacement, const NewtonStep& step, bool withTangent);
  Eigen::VectorXd freeResidual() const;  // R_f = f_int - f_ext on free dofs
  // max |K_ff diagonal| * max |x|: the force that round-off of the coordinates (eps |x|) makes
  // through the last assembled tangent, times 1/eps.
  double stiffnessForceScale() const;
  double lineSearch(const NewtonStep& step, const Eigen::VectorXd& du, const Eigen::VectorXd& rhs,
                    Eigen::VectorXd& displacement, double largestResidual);
  void addToFree(Eigen::VectorXd& displacement, const Eigen::VectorXd& du, double scale) const;
  void checkTangent(const NewtonStep& step, const Eigen::VectorXd& du,
                    const Eigen::VectorXd& displacement);
  void printWorstEquations(const Eigen::VectorXd& Kv, const Eigen::VectorXd& fd) const;

  NonlinearProblem& problem_;
  StepObserver& observer_;
  Clock::time_point runStart_;
  TangentSolver linear_;
  std::vector<TangentDumpRequest> dumps_;
  SystemMatrices tangent_;
  TangentOrientationWatch orientation_;  // the last tangents of a solve, for its failure message
  bool foldCandidate_ = false;           // the last solve ran out of iterations while switching
  Eigen::VectorXd internalForce_;
  double firstResidual_ = 0, firstEnergy_ = 0;
  double finalRelativeResidual_ = 0;
  Eigen::VectorXd externalForce_;
  Eigen::Matrix3Xd current_;
  Eigen::Matrix3Xd previous_;
  int assemblies_ = 0;
  double assemblySeconds_ = 0;
  bool extrapolatedStart_ = false;  // the next assembly is at an extrapolated first iterate
  double viscousFactor_ = 0;        // NewtonSpec::stabilization of the step being solved
  int startedStep_ = -1, startedAttempt_ = -1;  // the solve that set previous_ (x_n)
  struct {
    int step = -1, iteration = -1;
  } tangentCheck_;
};

}  // namespace cc
