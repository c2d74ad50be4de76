// Newton systems solved with an earlier factorization (issue 13, small and medium models).
// Within a Newton solve a new tangent K is solved by GMRES (Eigen's) preconditioned by the LU
// or Cholesky factor of an earlier tangent of that solve, instead of by a new factorization.
// Successive tangents of a Newton step differ little (on the ironing die model, 4 464
// equations, by 2e-6 relative from the second iteration on), so about ten GMRES iterations,
// each a triangular solve and a product with K, replace the factorization and its refined
// solve. A solve that has not converged after the iterations allowed is abandoned, and the
// caller factorizes K (TangentSolver).
#pragma once

#include <Eigen/Core>

#include "solver/linear_solver.hpp"

namespace cc {

// Relative residual the reusing GMRES solve reaches (preconditioned by the factor, i.e. close
// to the relative error of the solution): a new factorization's refined solve reaches 1e-14 to
// 1e-13, and Newton's quadratic tail and energy criterion (1e-16 of the first energy, an energy
// being a product of two residuals) see no difference at 1e-12.
inline constexpr double kReusedFactorTolerance = 1e-12;
// Relative true residual |b - K x| / |b| a reusing solve must reach as well (measured on the
// ironing die model at the tolerance above: at most 1.6e-11).
inline constexpr double kReusedFactorResidual = 1e-10;

struct ReusedFactorSolve {
  bool converged = false;
  int iterations = 0;
  Eigen::VectorXd solution;
};

// GMRES on matrix x = rhs, preconditioned by factor.applyFactor, from x = 0, without restart,
// for at most maxIterations iterations.
ReusedFactorSolve solveWithEarlierFactor(const SparseMatrix& matrix, LinearSolver& factor,
                                         const Eigen::VectorXd& rhs, int maxIterations);

}  // namespace cc
