// LinearSolver: the sparse direct solver behind Newton's method. CHOLMOD serves symmetric
// systems, UMFPACK unsymmetric ones; a distributed backend (PETSc) would implement the same
// interface. The symbolic analysis is redone only when the sparsity pattern changes.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

namespace cc {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// Work done by a solver, accumulated over its lifetime (benchmarks, progress line, tests).
struct LinearSolverStatistics {
  int analyses = 0;
  int factorizations = 0;  // attempted, including failed ones
  int failedFactorizations = 0;
  int solves = 0;
  double analysisSeconds = 0;
  double factorizationSeconds = 0;
  double solveSeconds = 0;

  LinearSolverStatistics& operator+=(const LinearSolverStatistics& other);
};

// Pivots smaller than this fraction of the largest one (reciprocal condition estimate of the
// factor: min/max of the diagonal of D in A = L D L^T or of U) carry no significant digits:
// the matrix is numerically singular (a free rigid-body mode, a missing support).
inline constexpr double kSingularPivotRatio = 1e-15;

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual std::string name() const = 0;
  // Symbolic analysis (ordering, elimination tree) for a new sparsity pattern. The matrix must
  // be square, compressed, with sorted row indices; symmetric solvers read its upper triangle.
  virtual void analyzePattern(const SparseMatrix& matrix) = 0;
  // Numeric factorization with the analyzed pattern; throws StepFailure(SingularSystem) when
  // the matrix is singular (or, for CHOLMOD, not positive definite). `matrix` must stay alive
  // and unchanged until the last solve() with this factorization (UMFPACK refines with it).
  virtual void factorize(const SparseMatrix& matrix) = 0;
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& rhs) = 0;

  const LinearSolverStatistics& statistics() const { return statistics_; }

 protected:
  LinearSolverStatistics statistics_;
};

// Fill-reducing ordering of CHOLMOD's symbolic analysis.
enum class CholmodOrdering {
  Amd,               // approximate minimum degree
  Metis,             // METIS nested dissection
  NestedDissection,  // CHOLMOD's NESDIS (METIS + constrained minimum degree)
  Automatic,         // CHOLMOD default: AMD, METIS tried as well when AMD's fill is high
};
// Measured on 3D solid meshes (scripts/bench_linear_solver, see the report in the solver
// notes): METIS gives the least fill and the fastest factorization for these problems.
inline constexpr CholmodOrdering kDefaultCholmodOrdering = CholmodOrdering::Metis;

std::unique_ptr<LinearSolver> makeCholmodSolver(CholmodOrdering ordering = kDefaultCholmodOrdering);
std::unique_ptr<LinearSolver> makeUmfpackSolver();

}  // namespace cc
