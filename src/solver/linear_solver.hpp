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

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual std::string name() const = 0;
  // Symbolic analysis (ordering, elimination tree) for a new sparsity pattern.
  virtual void analyzePattern(const SparseMatrix& matrix) = 0;
  // Numeric factorization with the current pattern; throws StepFailure(SingularSystem).
  virtual void factorize(const SparseMatrix& matrix) = 0;
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& rhs) = 0;
};

std::unique_ptr<LinearSolver> makeCholmodSolver();
std::unique_ptr<LinearSolver> makeUmfpackSolver();

}  // namespace cc
