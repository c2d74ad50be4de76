// TangentSolver: picks the direct solver for each Newton system. Symmetric tangents go to
// CHOLMOD; when CHOLMOD finds one not positive definite (legal with contact) UMFPACK takes
// over for the rest of the step; unsymmetric tangents go to UMFPACK. Each backend repeats its
// symbolic analysis only when SystemMatrices::patternVersion changes.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>

#include "fem/assembler.hpp"
#include "solver/linear_solver.hpp"

namespace cc {

class TangentSolver {
 public:
  TangentSolver();
  TangentSolver(std::unique_ptr<LinearSolver> symmetric, std::unique_ptr<LinearSolver> general);
  ~TangentSolver();

  // A new load step: try CHOLMOD again for symmetric systems.
  void beginStep() { choleskyRejected_ = false; }
  // Factorizes system.free (which must outlive the following solves). Throws
  // StepFailure(SingularSystem) naming what both backends reported.
  void factorize(const SystemMatrices& system);
  // Solution of K_ff x = rhs; throws StepFailure(NotFinite) if it is not finite.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs);

  // Sum over both backends.
  LinearSolverStatistics statistics() const;
  int choleskyFallbacks() const { return choleskyFallbacks_; }
  // "CHOLMOD" or "UMFPACK": the backend of the last successful factorization.
  std::string activeBackend() const { return active_ ? active_->name() : std::string(); }

 private:
  struct Backend {
    std::unique_ptr<LinearSolver> solver;
    std::uint64_t analyzedPattern = 0;  // SystemMatrices::patternVersion analyzed, 0 = none
  };
  void factorizeWith(Backend& backend, const SystemMatrices& system);

  Backend symmetric_;
  Backend general_;
  LinearSolver* active_ = nullptr;
  bool choleskyRejected_ = false;
  int choleskyFallbacks_ = 0;
  Eigen::Index size_ = 0;
};

}  // namespace cc
