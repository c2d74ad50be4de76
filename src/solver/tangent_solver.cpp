// Backend selection with CHOLMOD -> UMFPACK fallback and per-backend symbolic analysis reuse.
#include "solver/tangent_solver.hpp"

#include <algorithm>
#include <stdexcept>

#include "common/errors.hpp"

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
  return *this;
}

TangentSolver::TangentSolver() : TangentSolver(makeCholmodSolver(), makeUmfpackSolver()) {}

TangentSolver::TangentSolver(std::unique_ptr<LinearSolver> symmetric,
                             std::unique_ptr<LinearSolver> general)
    : symmetric_{std::move(symmetric)}, general_{std::move(general)} {}

TangentSolver::~TangentSolver() = default;

void TangentSolver::factorizeWith(Backend& backend, const SystemMatrices& system) {
  if (backend.analyzedPattern != system.patternVersion || system.patternVersion == 0) {
    backend.analyzedPattern = 0;
    backend.solver->analyzePattern(system.free);
    backend.analyzedPattern = system.patternVersion;
  }
  // Only one factor is alive at a time: the backend not used now gives its numeric factor back
  // before the new one is built (peak memory of a run that switches between CHOLMOD and
  // UMFPACK is one factor, not two; the symbolic analyses stay).
  Backend& idle = &backend == &symmetric_ ? general_ : symmetric_;
  idle.solver->releaseFactor();
  backend.solver->factorize(system.free);
  active_ = backend.solver.get();
}

void TangentSolver::factorize(const SystemMatrices& system) {
  active_ = nullptr;
  size_ = system.free.rows();
  if (size_ == 0) return;  // everything prescribed: nothing to solve
  std::string choleskyFailure;
  if (system.symmetric && !choleskyRejected_) {
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
    factorizeWith(general_, system);
  } catch (const StepFailure& failure) {
    if (choleskyFailure.empty()) throw;
    throw StepFailure(failure.kind(), choleskyFailure + "; " + failure.what());
  }
}

Eigen::VectorXd TangentSolver::solve(const Eigen::VectorXd& rhs) {
  if (size_ == 0) return Eigen::VectorXd();
  if (!active_) throw std::logic_error("TangentSolver: solve() without a factorization");
  Eigen::VectorXd solution = active_->solve(rhs);
  if (!solution.allFinite()) {
    throw StepFailure(FailureKind::NotFinite,
                      active_->name() + ": solution of the linear system is not finite");
  }
  return solution;
}

LinearSolverStatistics TangentSolver::statistics() const {
  LinearSolverStatistics total = symmetric_.solver->statistics();
  total += general_.solver->statistics();
  return total;
}

}  // namespace cc
