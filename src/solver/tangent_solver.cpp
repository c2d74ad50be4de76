// Backend selection (solver=), CHOLMOD -> UMFPACK fallback, Krylov -> direct fallback and
// per-backend symbolic analysis reuse.
#include "solver/tangent_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "common/errors.hpp"
#include "common/stopwatch.hpp"
#include "solver/factor_reuse.hpp"

namespace cc {

LinearSolverStatistics& LinearSolverStatistics::operator+=(const LinearSolverStatistics& other) {
  analyses += other.analyses;
  factorizations += other.factorizations;
  failedFactorizations += other.failedFactorizations;
  solves += other.solves;
  analysisSeconds += other.analysisSeconds;
  factorizationSeconds += other.factorizationSeconds;
  solveSeconds += other.solveSeconds;
  largestFactorBytes = std::max(largestFactorBytes, other.largestFactorBytes);
  largestFactorFlops = std::max(largestFactorFlops, other.largestFactorFlops);
  krylovIterations += other.krylovIterations;
  krylovFallbacks += other.krylovFallbacks;
  reusedPreconditioners += other.reusedPreconditioners;
  reusedOrderings += other.reusedOrderings;
  workspaceGrowths += other.workspaceGrowths;
  refinementSteps += other.refinementSteps;
  matrixBytesSent += other.matrixBytesSent;
  solutionBytesReceived += other.solutionBytesReceived;
  return *this;
}

namespace {

const char* methodSpelling(LinearSolverSpec::Method method) {
  using Method = LinearSolverSpec::Method;
  switch (method) {
    case Method::Auto:
      return "auto";
    case Method::Cholmod:
      return "cholmod";
    case Method::Umfpack:
      return "umfpack";
    case Method::Mumps:
      return "mumps";
    case Method::SuperluDist:
      return "superlu_dist";
    case Method::Amg:
      return "amg";
    case Method::Gamg:
      return "gamg";
  }
  return "?";
}

}  // namespace

TangentSolver::TangentSolver() : TangentSolver(makeCholmodSolver(), makeUmfpackSolver()) {}

TangentSolver::TangentSolver(std::unique_ptr<LinearSolver> symmetric,
                             std::unique_ptr<LinearSolver> general)
    : symmetric_{std::move(symmetric)}, general_{std::move(general)} {}

TangentSolver::TangentSolver(LinearSolverSpec::Method method) : TangentSolver() {
  method_ = method;
}

TangentSolver::~TangentSolver() = default;

void TangentSolver::setLayout(const SystemLayout& layout) {
  layout_ = layout;
  distributed_ = !layout_.nodeOwner.empty();
  if (petsc_.solver) petsc_.solver->setLayout(layout_);
  if (mumpsDirect_.solver) mumpsDirect_.solver->setLayout(layout_);
}

void TangentSolver::releaseOthers(const Backend& keep) {
  // Only one factor is alive at a time: the backends not used now give their numeric factor
  // back before the new one is built (peak memory of a run that switches between backends is
  // one factor, not two; the symbolic analyses stay).
  for (Backend* backend : {&symmetric_, &general_, &petsc_, &mumpsDirect_}) {
    if (backend != &keep && backend->solver) backend->solver->releaseFactor();
  }
}

void TangentSolver::factorizeWith(Backend& backend, const SystemMatrices& system) {
  if (backend.analyzedPattern != system.patternVersion || system.patternVersion == 0) {
    backend.analyzedPattern = 0;
    backend.solver->analyzePattern(system.free);
    backend.analyzedPattern = system.patternVersion;
  }
  releaseOthers(backend);
  backend.solver->factorize(system.free);
  active_ = backend.solver.get();
}

bool TangentSolver::usesPetsc(Eigen::Index size) {
  using Method = LinearSolverSpec::Method;
  const bool iterativeBySize = method_ == Method::Auto && size >= kIterativeBreakEven;
  const bool gamgFirst = iterativeBySize && size >= autoRule_.gamgFrom &&
                         (distributed_ || !autoRule_.gamgNeedsSeveralProcesses);
  // On several processes every solve is PETSc's: CHOLMOD and UMFPACK work on one process, so
  // auto below the break-even, cholmod and umfpack mean MUMPS (distributed LU) there.
  const bool petsc = distributed_ || method_ == Method::Mumps || method_ == Method::SuperluDist ||
                     method_ == Method::Amg || method_ == Method::Gamg || iterativeBySize;
  if (petsc && !petsc_.solver) {
    const PetscMethod petscMethod = method_ == Method::SuperluDist ? PetscMethod::SuperluDist
                                    : method_ == Method::Gamg || gamgFirst ? PetscMethod::Gamg
                                    : method_ == Method::Amg || iterativeBySize
                                        ? PetscMethod::BoomerAmg
                                        : PetscMethod::Mumps;
    attachPetsc(petscMethod);
    gamgProbation_ = gamgFirst;
  }
  if (choice_.empty()) {
    const std::string backend = petsc ? petsc_.solver->name() : directSolvers();
    choice_ = fmt::format("{} -> {}", methodSpelling(method_), backend);
    if (method_ == Method::Auto) {
      choice_ += fmt::format(" ({} equations {} {}", size, size >= kIterativeBreakEven ? ">=" : "<",
                             kIterativeBreakEven);
      if (gamgFirst) {
        choice_ += fmt::format(
            "; GAMG from {}, BoomerAMG once a new GAMG hierarchy converges slower than {} "
            "decades per Krylov iteration",
            autoRule_.gamgFrom, autoRule_.gamgSlowestRate);
      }
      if (size >= kUnsymmetricMumpsBreakEven && !distributed_) {
        choice_ +=
            fmt::format("; unsymmetric systems to MUMPS from {}", kUnsymmetricMumpsBreakEven);
      }
      choice_ += ")";
    }
    if (distributed_) choice_ += " on several processes";
    if (petsc_.solver && petsc_.solver->iterative()) {
      choice_ += fmt::format("; a stalled Krylov solve falls back to {}", directSolvers());
    }
    if (notify_) notify_("linear solver: " + choice_);
  }
  return petsc;
}

void TangentSolver::attachPetsc(PetscMethod method) {
  petsc_.solver = makePetscSolver(method);
  petsc_.analyzedPattern = 0;
  petsc_.solver->setLayout(layout_);
  if (stopPoll_) petsc_.solver->setStopPoll(stopPoll_);
}

void TangentSolver::setStopPoll(std::function<bool()> poll) {
  stopPoll_ = std::move(poll);
  if (petsc_.solver) petsc_.solver->setStopPoll(stopPoll_);
}

TangentSolver::Backend& TangentSolver::mumpsDirect() {
  if (!mumpsDirect_.solver) {
    mumpsDirect_.solver = makePetscSolver(PetscMethod::Mumps);
    mumpsDirect_.solver->setLayout(layout_);
  }
  return mumpsDirect_;
}

bool TangentSolver::autoPrefersMumps() {
  if (method_ != LinearSolverSpec::Method::Auto || size_ < kUnsymmetricMumpsBreakEven ||
      mumpsUnavailable_) {
    return false;
  }
  // MUMPS is only faster here: when PETSc cannot be loaded or started (a build without it, or
  // too little memory left to map its libraries and start MPI), UMFPACK solves instead.
  try {
    mumpsDirect();
    return true;
  } catch (const std::runtime_error& error) {
    mumpsUnavailable_ = true;
    if (notify_) notify_(fmt::format("{}; unsymmetric systems go to UMFPACK", error.what()));
    return false;
  }
}

std::string TangentSolver::directSolvers() const {
  if (distributed_) return "MUMPS";
  if (method_ == LinearSolverSpec::Method::Umfpack) return "UMFPACK";
  const bool mumps = method_ == LinearSolverSpec::Method::Auto &&
                     size_ >= kUnsymmetricMumpsBreakEven && !mumpsUnavailable_;
  return mumps ? "CHOLMOD/MUMPS" : "CHOLMOD/UMFPACK";
}

void TangentSolver::factorizeDirect(const SystemMatrices& system) {
  if (distributed_) {
    factorizeWith(mumpsDirect(), system);
    return;
  }
  std::string choleskyFailure;
  if (system.symmetric && !choleskyRejected_ && method_ != LinearSolverSpec::Method::Umfpack) {
    try {
      factorizeWith(symmetric_, system);
      return;
    } catch (const StepFailure& failure) {
      if (failure.kind() != FailureKind::SingularSystem) throw;
      choleskyFailure = failure.what();
      choleskyRejected_ = true;
      ++choleskyFallbacks_;
    }
  }
  try {
    factorizeWith(autoPrefersMumps() ? mumpsDirect() : general_, system);
  } catch (const StepFailure& failure) {
    if (choleskyFailure.empty()) throw;
    throw StepFailure(failure.kind(), choleskyFailure + "; " + failure.what());
  }
}

bool TangentSolver::canReuseFactor(const SystemMatrices& system) const {
  return reuseFactors_ && !refactorizeNext_ && active_ && reusableFactor_ &&
         system.free.rows() == size_;
}

void TangentSolver::recordFactor() {
  // Only the serial direct pair: a PETSc backend keeps its own copy of the matrix (and an
  // iterative one its own reuse of the AMG hierarchy).
  const bool serialDirect =
      active_ && !distributed_ &&
      (active_ == symmetric_.solver.get() || active_ == general_.solver.get());
  reusableFactor_ = serialDirect;
  refactorizeNext_ = false;
}

void TangentSolver::factorize(const SystemMatrices& system) {
  reusing_ = canReuseFactor(system);
  system_ = &system;
  if (reusing_) return;
  active_ = nullptr;
  reusableFactor_ = false;
  size_ = system.free.rows();
  if (size_ == 0) return;  // everything prescribed: nothing to solve
  if (usesPetsc(size_)) {
    const int kept = petsc_.solver->statistics().reusedPreconditioners;
    try {
      factorizeWith(petsc_, system);
    } catch (const StepFailure& failure) {
      if (failure.kind() != FailureKind::SingularSystem || !petsc_.solver->iterative()) throw;
      setUpFailed(failure);
      recordFactor();
      return;
    }
    freshHierarchy_ = petsc_.solver->statistics().reusedPreconditioners == kept;
  } else {
    factorizeDirect(system);
  }
  recordFactor();
}

Eigen::VectorXd TangentSolver::solveWithReusedFactor(const Eigen::VectorXd& rhs) {
  const auto start = std::chrono::steady_clock::now();
  const ReusedFactorSolve reused =
      solveWithEarlierFactor(system_->free, *active_, rhs, kReusedFactorIterations);
  reuseKrylovIterations_ += reused.iterations;
  reuseSeconds_ += secondsSince(start);
  if (reused.converged) {
    ++reusedFactors_;
    // The tangents drift further from the factor as Newton goes on: one that needed more than
    // half the allowance is factorized next time rather than risk a wasted attempt.
    if (reused.iterations > kReusedFactorIterations / 2) refactorizeNext_ = true;
    return reused.solution;
  }
  reusing_ = false;
  active_ = nullptr;
  factorizeDirect(*system_);
  recordFactor();
  return active_->solve(rhs);
}

void TangentSolver::setKrylovLimits() {
  active_->setRelativeTolerance(forcing_);
  int limit = iterationLimit_ > 0 ? iterationLimit_ : kKrylovIterationLimit;
  if (iterationLimit_ == 0 && onGamgProbation()) {
    // The iterations a solve at the rule's slowest rate needs to reach the tolerance (with a
    // kept hierarchy too: one that misses it is rebuilt, by leaveGamg, before it is judged).
    const double decades = std::max(1.0, -std::log10(forcing_));
    limit = std::min(limit, static_cast<int>(std::ceil(decades / autoRule_.gamgSlowestRate)));
  }
  active_->setIterationLimit(limit);
  krylovLimit_ = limit;
}

Eigen::VectorXd TangentSolver::solve(const Eigen::VectorXd& rhs) {
  if (size_ == 0) return Eigen::VectorXd();
  if (!active_) throw std::logic_error("TangentSolver: solve() without a factorization");
  Eigen::VectorXd solution;
  if (active_->iterative()) setKrylovLimits();
  try {
    solution = reusing_ ? solveWithReusedFactor(rhs) : active_->solve(rhs);
  } catch (const KrylovFailure& failure) {
    if (onGamgProbation()) return leaveGamg(rhs, failure);
    if (active_->iterative()) {
      // A Krylov solve that stalled. GAMG stalled on a 3D bulk mesh under a stiff sliding die
      // (341 k equations), where BoomerAMG needed 5-6 times fewer Krylov iterations and
      // completed (solvers.md).
      const bool gamg = active_->name().find("GAMG") != std::string::npos;
      factorizeDirectlyThisIteration(failure.what(),
                                     gamg ? " (if GAMG stalls again, try solver=amg)" : "");
    } else {
      factorizeAfterDirectMiss(failure);
    }
    solution = active_->solve(rhs);
  }
  if (!solution.allFinite()) {
    throw StepFailure(FailureKind::NotFinite,
                      active_->name() + ": solution of the linear system is not finite");
  }
  return solution;
}

Eigen::VectorXd TangentSolver::leaveGamg(const Eigen::VectorXd& rhs, const KrylovFailure& failure) {
  if (!freshHierarchy_) {
    // A kept hierarchy may only be stale: GAMG gets a new one (the failed solve asked for it)
    // and is judged on that.
    factorizeWith(petsc_, *system_);
    freshHierarchy_ = true;
    return solve(rhs);
  }
  if (notify_) {
    notify_(
        fmt::format("{}: a new GAMG hierarchy missed its allowance of {} iterations ({} "
                    "decades per iteration); GMRES+BoomerAMG solves this iteration and the rest "
                    "of the run",
                    failure.what(), krylovLimit_, autoRule_.gamgSlowestRate));
  }
  replaceGamgWithBoomerAmg("GAMG too slow");
  factorizeWith(petsc_, *system_);
  return solve(rhs);
}

// MUMPS (or SuperLU_dist) solved a factorized tangent to a residual far above round-off: the
// tangent is too ill-conditioned for its pivoting. Refactorizing with the same solver, as after
// a Krylov stall, misses again, and the second miss left the run as an internal error (a
// 33 k-equation ironing drag near a fold, MUMPS at 1.6e-8 of the right-hand side;
// docs/verification/sliding.md, forty-seventh session). On one process UMFPACK, whose solve
// refines against the matrix, is factorized for this iteration; on several, where MUMPS is the only
// direct solver, the iteration fails as a singular system, which Newton answers with its retries
// and cut-backs.
void TangentSolver::factorizeAfterDirectMiss(const KrylovFailure& failure) {
  const std::string what = failure.what();
  if (distributed_) {
    throw StepFailure(FailureKind::SingularSystem,
                      what + ": the tangent is numerically singular for the direct solver");
  }
  ++krylovFallbacks_;
  if (notify_) notify_(what + "; solving this iteration with UMFPACK");
  factorizeWith(general_, *system_);
}

void TangentSolver::replaceGamgWithBoomerAmg(const std::string& why) {
  retiredStatistics_ += petsc_.solver->statistics();
  // The run's record of the choice (printed, and the results file's summary) says so too.
  choice_ +=
      fmt::format("; GMRES+BoomerAMG from Krylov solve {} on, {}", retiredStatistics_.solves, why);
  if (notify_) notify_("linear solver: " + choice_);
  gamgProbation_ = false;
  active_ = nullptr;
  attachPetsc(PetscMethod::BoomerAmg);
}

void TangentSolver::setUpFailed(const StepFailure& failure) {
  // An AMG set-up can fail on a regular tangent: with PETSc 3.18, GAMG with SOR smoothers on
  // two processes fails in every set-up (SUBPC_ERROR) of the 11 k scaling deck, which MUMPS
  // solves. So a direct solver decides for this iteration, and says "singular" itself if the
  // tangent is; auto's GAMG on probation gives way to BoomerAMG for the rest of the run.
  active_ = nullptr;
  if (gamgProbation_) {
    if (notify_) {
      notify_(fmt::format("{}; GMRES+BoomerAMG solves this iteration and the rest of the run",
                          failure.what()));
    }
    replaceGamgWithBoomerAmg("GAMG's set-up failed");
    factorizeWith(petsc_, *system_);
    return;
  }
  factorizeDirectlyThisIteration(failure.what(), "");
}

void TangentSolver::factorizeDirectlyThisIteration(const std::string& why,
                                                   const std::string& advice) {
  // CHOLMOD/UMFPACK, or MUMPS on several processes.
  ++krylovFallbacks_;
  if (notify_) {
    notify_(fmt::format("{}; solving this iteration with {}{}", why, directSolvers(), advice));
  }
  factorizeDirect(*system_);
}

LinearSolverStatistics TangentSolver::statistics() const {
  LinearSolverStatistics total = symmetric_.solver->statistics();
  total += general_.solver->statistics();
  if (petsc_.solver) total += petsc_.solver->statistics();
  total += retiredStatistics_;
  if (mumpsDirect_.solver) total += mumpsDirect_.solver->statistics();
  total.krylovFallbacks = krylovFallbacks_;
  total.reusedPreconditioners += reusedFactors_;
  total.krylovIterations += reuseKrylovIterations_;
  total.solves += reusedFactors_;
  total.solveSeconds += reuseSeconds_;
  return total;
}

}  // namespace cc
