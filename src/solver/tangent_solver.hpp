// TangentSolver: picks the linear solver for each Newton system (deck: `solve solver=...`).
// The direct pair: symmetric tangents go to CHOLMOD; when CHOLMOD finds one not positive
// definite (legal with contact) UMFPACK takes over for the rest of the step; unsymmetric
// tangents go to UMFPACK (under `solver=auto` from kUnsymmetricMumpsBreakEven equations to
// MUMPS instead). `solver=auto` uses the direct pair below kIterativeBreakEven free
// equations and GMRES + BoomerAMG (PETSc, hypre) above it; on several processes from
// kGamgFirstFrom it starts with GMRES + GAMG and keeps it while GAMG converges fast enough
// (AutoPreconditionerRule). An iterative solve that stalls or diverges, or an AMG set-up that
// fails, is redone with the direct pair for that iteration, and the note says so. Each
// backend repeats its symbolic analysis only when SystemMatrices::patternVersion changes. On
// several processes (SystemLayout::nodeOwner given) every system goes to PETSc: MUMPS where the
// serial direct pair would be used, and for the fallback of a failed Krylov solve.
// Within a Newton solve, CHOLMOD's and UMFPACK's factor serves the later tangents: each is
// solved by GMRES preconditioned by the kept factor (factor_reuse.hpp) and factorized only when
// that solve does not converge within kReusedFactorIterations (or the previous one needed more
// than half of them). Contact changes the pattern of the tangent, not its equations, so the
// factor serves across pattern changes too; the new pattern is analyzed when it is factorized.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "fem/assembler.hpp"
#include "solver/linear_solver.hpp"
#include "spec/problem_spec.hpp"

namespace cc {

// Free equations from which `solver=auto` solves iteratively, with GMRES + BoomerAMG. Measured
// on dumped tangents of the scaling decks with the node blocks (docs/performance/solvers.md,
// twenty-ninth session, one thread, CPU seconds per system, stick / slip): 14 k equations
// UMFPACK 0.24 / 0.32, BoomerAMG 0.43 / 0.39, GAMG 0.76 / 0.64; 45 k UMFPACK 1.47 / 1.31 (less
// without the analysis that Newton reuses, and a kept factor serves later tangents), MUMPS
// 1.23 / 1.21, BoomerAMG 0.90 / 1.21, GAMG 1.61 / 2.28. Whole runs, one thread: the thin 57 k
// scaling deck (45 242 equations) BoomerAMG 42.1-51.4 s, GAMG 50.6 s, the direct pair 53.4 s
// (59, 60 and 56 Newton iterations): even at 45 k, so the break-even stays. Above it BoomerAMG,
// not GAMG: one process, thin, 0.5-0.8 times GAMG's CPU per system up to 342 k equations; on
// the bulk die (bulk_79k.deck) BoomerAMG 91.3 s and 42 iterations, GAMG 1038 s, 102 iterations
// and a cut-back; on two processes 36.0 against 39.8 s (thin) and 63.8 s against 703.5 s with
// six stalled Krylov solves (bulk). Two processes on thin models from a few hundred thousand
// equations, where GAMG is faster, start with GAMG instead (kGamgFirstFrom). Every paper and
// regression deck is far below the break-even (at most ~20 k).
inline constexpr Eigen::Index kIterativeBreakEven = 50000;
static_assert(kIterativeBreakEven == kMemoryBoundSystemFrom,
              "linear_solver.hpp: memory-bound sizes start where the direct solvers end");

// Free equations from which `solver=auto` on several processes starts with GMRES + GAMG instead
// of BoomerAMG, and the slowest convergence it accepts from GAMG: a solve with a new GAMG
// hierarchy that has not reached its tolerance after log10(1 / tolerance) / kGamgSlowestRate
// Krylov iterations is redone with BoomerAMG, which serves the rest of the run (a solve with a
// kept hierarchy that misses the allowance is repeated with a new one first). Thin scaling
// decks on two processes (thirty-fourth session, `--threads 1`, whole runs): 125 k BoomerAMG
// 62.7 s against GAMG 68.9 s; 388 k (twenty-ninth session) 365.9 against 304.6 s; 1.13 M 18.4-19.3
// against 13.1 min. GAMG's rate there: 0.13-0.47 decades per iteration in every solve of the
// 125 k deck. On the bulk die (bulk_79k.deck) it was 0.04-0.10 from the first solve (0.059),
// against BoomerAMG's 0.3-0.4, and GAMG stalled in the first drag step (the whole run on two
// processes: 703.5 s against BoomerAMG's 63.8 s). On the bulk die the switch came in the first
// solve and cost one GAMG set-up and 43 iterations: 5 % of the run at 341 k (207.7 s against
// 197.4 s with BoomerAMG throughout), 48 s at 1.2 M (938.3 against 890.1 s back to back). One
// process: BoomerAMG was the faster on thin decks at every size measured (to 1.13 M), so it
// starts there.
inline constexpr Eigen::Index kGamgFirstFrom = 250000;
inline constexpr double kGamgSlowestRate = 0.07;

// Which preconditioner `solver=auto` starts with above kIterativeBreakEven (the measured
// defaults above; tests move them).
struct AutoPreconditionerRule {
  Eigen::Index gamgFrom = kGamgFirstFrom;
  bool gamgNeedsSeveralProcesses = true;
  double gamgSlowestRate = kGamgSlowestRate;  // decades of residual per Krylov iteration
};

// Free equations from which `solver=auto` factorizes unsymmetric systems (friction) with MUMPS
// (PETSc, one process) instead of UMFPACK. The whole scaling runs, one thread, the two solvers
// back to back (`run --solver umfpack|mumps --cost`, load average 6-7, 2026-11-25): 8 k
// equations 5.2-6.1 against 5.6-5.8 CPU s (even); 14 k 23.6 against 8.4; 45 k 117.8 against 44.1
// (idle: 89.0 against 32.6 s of solving, docs/performance/distributed.md), with the same Newton
// iterations. UMFPACK's allocation of its workspace at every factorization (a third of its time
// as system time) is most of the difference.
inline constexpr Eigen::Index kUnsymmetricMumpsBreakEven = 12000;

// GMRES iterations a solve with an earlier factor may take (factor_reuse.hpp) before the
// tangent is factorized after all. Each costs a triangular solve with the factor and a product
// with the tangent: on the ironing die model (4 464 equations) ~2 ms against ~45 ms for a
// factorization and ~10 ms for its refined solve, on example 6.1 (2 032) ~0.13 against ~5.
// 40 (and a new factor after a solve that needed more than 20) against 20 (10): the die model
// 1-11 % less CPU time in five pairs run alternately (twenty-third and twenty-fourth sessions),
// 6.1 2-3 % in three, the same Newton iterations (docs/performance/solvers.md).
inline constexpr int kReusedFactorIterations = 40;

class TangentSolver {
 public:
  TangentSolver();  // the direct pair
  TangentSolver(std::unique_ptr<LinearSolver> symmetric, std::unique_ptr<LinearSolver> general);
  explicit TangentSolver(LinearSolverSpec::Method method);
  ~TangentSolver();

  // A new Newton solve (step, attempt or re-solve): try CHOLMOD again for symmetric systems,
  // and factorize its first tangent, so that a step's result depends on its start only (a cut
  // step ends bit for bit where the same sub-steps taken plainly end, a restart where the run).
  void beginStep() {
    choleskyRejected_ = false;
    reusableFactor_ = false;
  }
  // Where the equations sit (iterative backends: node blocks and rigid-body modes).
  void setLayout(const SystemLayout& layout);
  // Relative residual the next iterative solves must reach (Newton's forcing term).
  void setForcing(double relativeTolerance) { forcing_ = relativeTolerance; }
  // Krylov iterations after which a solve counts as stalled (default: the backend's).
  void setKrylovIterationLimit(int iterations) { iterationLimit_ = iterations; }
  void setAutoPreconditionerRule(const AutoPreconditionerRule& rule) { autoRule_ = rule; }
  // Whether CHOLMOD's and UMFPACK's factors are reused for later tangents (default yes).
  void setFactorReuse(bool reuse) { reuseFactors_ = reuse; }
  // Receives one line for every choice and fallback (printed and logged by the command).
  void setNotifier(std::function<void(const std::string&)> notify) { notify_ = std::move(notify); }
  // Polled between Krylov iterations (LinearSolver::setStopPoll): true ends the solve with
  // SolveInterrupted, which solve() passes on instead of falling back to a direct solver.
  void setStopPoll(std::function<bool()> poll);
  // Factorizes system.free (which must outlive the following solves). Throws
  // StepFailure(SingularSystem) naming what both backends reported.
  void factorize(const SystemMatrices& system);
  // Solution of K_ff x = rhs; throws StepFailure(NotFinite) if it is not finite.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs);
  // True when the next solve is iterative (Newton then sets a forcing term).
  bool iterative() const { return active_ && active_->iterative(); }
  // The last iterative solve's report (empty after a direct one).
  KrylovReport lastSolve() const { return active_ ? active_->lastSolve() : KrylovReport{}; }
  // The sign of the determinant of the tangent the last solve used, where its direct backend
  // factorized it and can tell (UMFPACK, MUMPS; CHOLMOD's factor proves it positive); nothing
  // after an iterative solve or one with a reused factor (the tangent itself was not factorized).
  std::optional<int> determinantSign() {
    return active_ && !reusing_ ? active_->determinantSign() : std::nullopt;
  }

  // Sum over all backends.
  LinearSolverStatistics statistics() const;
  int choleskyFallbacks() const { return choleskyFallbacks_; }
  // "CHOLMOD", "UMFPACK", "MUMPS", "GMRES+BoomerAMG", ...: the backend of the last successful
  // factorization.
  std::string activeBackend() const { return active_ ? active_->name() : std::string(); }
  // What `solver=` asked for and what it resolved to, e.g. "auto -> CHOLMOD/UMFPACK (6171
  // equations < 150000)"; empty before the first factorization.
  const std::string& choice() const { return choice_; }

 private:
  struct Backend {
    std::unique_ptr<LinearSolver> solver;
    std::uint64_t analyzedPattern = 0;  // SystemMatrices::patternVersion analyzed, 0 = none
  };
  void factorizeWith(Backend& backend, const SystemMatrices& system);
  void factorizeDirect(const SystemMatrices& system);
  bool usesPetsc(Eigen::Index size);
  void releaseOthers(const Backend& keep);
  bool canReuseFactor(const SystemMatrices& system) const;
  void recordFactor();
  Eigen::VectorXd solveWithReusedFactor(const Eigen::VectorXd& rhs);
  void setKrylovLimits();
  void attachPetsc(PetscMethod method);
  bool onGamgProbation() const { return gamgProbation_ && active_ == petsc_.solver.get(); }
  Eigen::VectorXd leaveGamg(const Eigen::VectorXd& rhs, const KrylovFailure& failure);
  // A PETSc direct solve that missed (its residual far above round-off): UMFPACK factorizes
  // the tangent on one process (solve() then solves with it), else a singular-system failure
  // of the iteration.
  void factorizeAfterDirectMiss(const KrylovFailure& failure);
  void replaceGamgWithBoomerAmg(const std::string& why);
  // The iterative PETSc backend's set-up failed with SingularSystem: a direct solver (or, for
  // auto's GAMG, BoomerAMG) factorizes this tangent instead.
  void setUpFailed(const StepFailure& failure);
  // A failed iterative solve or set-up (`why`): the direct solvers factorize this tangent, and
  // the note says so (with `advice`).
  void factorizeDirectlyThisIteration(const std::string& why, const std::string& advice);

  LinearSolverSpec::Method method_ = LinearSolverSpec::Method::Cholmod;
  Backend symmetric_;
  Backend general_;
  Backend petsc_;  // created on first use
  // auto's GAMG (AutoPreconditionerRule): on probation until a solve with a new hierarchy
  // converges slower than the rule's rate, then replaced by BoomerAMG for the rest of the run.
  // freshHierarchy_: the last factorization built its hierarchy (a kept one that misses the
  // rate may only be stale: it is rebuilt and the solve repeated first).
  AutoPreconditionerRule autoRule_;
  bool gamgProbation_ = false;
  bool freshHierarchy_ = false;
  int krylovLimit_ = 0;                       // the iteration limit of the last iterative solve
  LinearSolverStatistics retiredStatistics_;  // of the GAMG backend replaced
  // MUMPS as a direct solver (created on first use): on several processes for every direct
  // solve; on one, for large unsymmetric systems under auto (kUnsymmetricMumpsBreakEven).
  Backend mumpsDirect_;
  Backend& mumpsDirect();
  // auto, one process: whether this unsymmetric system goes to MUMPS (from
  // kUnsymmetricMumpsBreakEven equations, if PETSc can be loaded; otherwise UMFPACK, once said).
  bool autoPrefersMumps();
  bool mumpsUnavailable_ = false;
  // The direct solvers factorizeDirect uses now, e.g. "CHOLMOD/UMFPACK".
  std::string directSolvers() const;
  bool distributed_ = false;  // the layout distributes the rows over several processes
  LinearSolver* active_ = nullptr;
  const SystemMatrices* system_ = nullptr;
  bool choleskyRejected_ = false;
  int choleskyFallbacks_ = 0;
  int krylovFallbacks_ = 0;
  Eigen::Index size_ = 0;
  double forcing_ = 1e-8;
  int iterationLimit_ = 0;  // 0 = the backend's default
  SystemLayout layout_;
  std::string choice_;
  // Factor reuse (factor_reuse.hpp): whether active_ holds a factor of the serial direct pair,
  // whether the next solve uses it, and whether the next factorize() must not.
  bool reuseFactors_ = true;
  bool reusableFactor_ = false;
  bool reusing_ = false;
  bool refactorizeNext_ = false;
  int reusedFactors_ = 0;
  long reuseKrylovIterations_ = 0;
  double reuseSeconds_ = 0;
  std::function<void(const std::string&)> notify_;
  std::function<bool()> stopPoll_;
};

}  // namespace cc
