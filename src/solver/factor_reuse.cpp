// GMRES preconditioned by an earlier factor (factor_reuse.hpp), with Eigen's GMRES.
#include "solver/factor_reuse.hpp"

#include <unsupported/Eigen/IterativeSolvers>
#include <utility>

namespace cc {

namespace {

// Largest |entry| between which squares of the entries neither underflow nor overflow, with
// room for the sums of a norm.
constexpr std::pair<double, double> kSafeNormRange{1e-140, 1e140};

// Eigen's preconditioner concept over LinearSolver::applyFactor: the factor is already there,
// so analysis and factorization are nothing.
class EarlierFactor {
 public:
  EarlierFactor() = default;
  void bind(LinearSolver& factor) { factor_ = &factor; }
  template <typename Matrix>
  EarlierFactor& analyzePattern(const Matrix&) {
    return *this;
  }
  template <typename Matrix>
  EarlierFactor& factorize(const Matrix&) {
    return *this;
  }
  template <typename Matrix>
  EarlierFactor& compute(const Matrix&) {
    return *this;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& residual) const {
    return factor_->applyFactor(residual);
  }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

 private:
  LinearSolver* factor_ = nullptr;
};

}  // namespace

ReusedFactorSolve solveWithEarlierFactor(const SparseMatrix& matrix, LinearSolver& factor,
                                         const Eigen::VectorXd& rhs, int maxIterations) {
  Eigen::GMRES<SparseMatrix, EarlierFactor> gmres;
  gmres.preconditioner().bind(factor);
  gmres.setTolerance(kReusedFactorTolerance);
  gmres.setMaxIterations(maxIterations);
  gmres.set_restart(maxIterations);  // no restart: the iterations are few
  gmres.compute(matrix);
  ReusedFactorSolve result;
  // Eigen's GMRES measures vectors with norm(), which squares their entries: a right-hand side
  // whose squares underflow (a model of modulus 1e-300) passed for zero and came back as x = 0.
  // Outside the range where norm() is exact the caller factorizes instead.
  const double largest = rhs.cwiseAbs().maxCoeff();
  if (!(largest > kSafeNormRange.first && largest < kSafeNormRange.second)) return result;
  result.solution = gmres.solve(rhs);
  result.iterations = static_cast<int>(gmres.iterations());
  // Left-preconditioned GMRES measures |M^-1 r|, which a poor factor could make small while
  // r is not: the solution counts only with a small true residual as well.
  result.converged = gmres.info() == Eigen::Success && result.solution.allFinite() &&
                     (rhs - matrix * result.solution).norm() <= kReusedFactorResidual * rhs.norm();
  return result;
}

}  // namespace cc
