// A stable truss of n x n x n nodes as a test system for the linear solvers (serial and
// distributed PETSc tests): axial springs along the edges and face diagonals of every cell, so
// each 3 x 3 block is k d d^T and the free lattice has exactly the six rigid-body modes as
// nullspace. The nodes of the bottom layer z = 0 are fixed; their dofs are not equations.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "fem/assembler.hpp"
#include "solver/linear_solver.hpp"
#include "solver/tangent_solver.hpp"

namespace cc::test {

struct Lattice {
  SystemMatrices system;
  SystemLayout layout;
};

struct LatticeOptions {
  // An unsymmetric coupling skew * (e_x e_y^T - e_y e_x^T) added to the springs of the top
  // layer (like the frictional slip tangent of a contact surface), keeping the pattern.
  double skew = 0.0;
  // Factor of the spring between nodes a and b (empty: 1). A factor 0 keeps the spring's
  // entries in the pattern as zeros: a share of the system that other processes complete.
  std::function<double(int a, int b)> weight;
  // Springs between further node pairs (a, b), weighted like the others.
  std::vector<std::pair<int, int>> extraSprings;
};

inline int latticeNode(int n, int i, int j, int k) {
  return i + n * (j + n * k);
}

inline Lattice lattice(int n, const LatticeOptions& options) {
  Lattice result;
  const int nodes = n * n * n;
  result.layout.coordinates.resize(3, nodes);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) result.layout.coordinates.col(latticeNode(n, i, j, k)) << i, j, k;
  std::vector<int> equation(3 * nodes, -1);
  for (int d = 0; d < 3 * nodes; ++d) {
    if (d / 3 >= n * n) {  // not on the bottom layer
      equation[d] = static_cast<int>(result.layout.freeDofs.size());
      result.layout.freeDofs.push_back(d);
    }
  }
  std::vector<Eigen::Triplet<double>> entries;
  auto spring = [&](int a, int b) {
    const Eigen::Vector3d d =
        (result.layout.coordinates.col(b) - result.layout.coordinates.col(a)).normalized();
    Eigen::Matrix3d block = d * d.transpose();
    const bool onTop = a / (n * n) == n - 1 && b / (n * n) == n - 1;
    if (onTop) block(0, 1) += options.skew, block(1, 0) -= options.skew;
    if (options.weight) block *= options.weight(a, b);
    const int ends[2] = {a, b};
    for (int p = 0; p < 2; ++p)
      for (int q = 0; q < 2; ++q)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) {
            const int row = equation[3 * ends[p] + r], col = equation[3 * ends[q] + c];
            if (row >= 0 && col >= 0) {
              entries.emplace_back(row, col, (p == q ? 1.0 : -1.0) * block(r, c));
            }
          }
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = latticeNode(n, i, j, k);
        if (i + 1 < n) spring(a, latticeNode(n, i + 1, j, k));
        if (j + 1 < n) spring(a, latticeNode(n, i, j + 1, k));
        if (k + 1 < n) spring(a, latticeNode(n, i, j, k + 1));
        if (i + 1 < n && j + 1 < n) {
          spring(a, latticeNode(n, i + 1, j + 1, k));
          spring(latticeNode(n, i + 1, j, k), latticeNode(n, i, j + 1, k));
        }
        if (i + 1 < n && k + 1 < n) {
          spring(a, latticeNode(n, i + 1, j, k + 1));
          spring(latticeNode(n, i + 1, j, k), latticeNode(n, i, j, k + 1));
        }
        if (j + 1 < n && k + 1 < n) {
          spring(a, latticeNode(n, i, j + 1, k + 1));
          spring(latticeNode(n, i, j + 1, k), latticeNode(n, i, j, k + 1));
        }
      }
  for (const auto& [a, b] : options.extraSprings) spring(a, b);
  const int size = static_cast<int>(result.layout.freeDofs.size());
  result.system.free.resize(size, size);
  result.system.free.setFromTriplets(entries.begin(), entries.end());
  result.system.free.makeCompressed();
  result.system.symmetric = options.skew == 0.0;
  result.system.patternVersion = 1;
  return result;
}

inline Lattice lattice(int n, double skew = 0.0) {
  LatticeOptions options;
  options.skew = skew;
  return lattice(n, options);
}

inline Eigen::VectorXd rightHandSide(Eigen::Index size) {
  Eigen::VectorXd rhs(size);
  for (Eigen::Index k = 0; k < size; ++k) rhs[k] = std::sin(1.0 + static_cast<double>(k));
  return rhs;
}

// Largest over smallest singular value (dense SVD: small systems only).
inline double conditionNumber(const SparseMatrix& matrix) {
  const Eigen::MatrixXd dense(matrix);
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(dense);
  return svd.singularValues()(0) / svd.singularValues()(svd.singularValues().size() - 1);
}

// The reference solution: CHOLMOD on the whole (symmetric) system.
inline Eigen::VectorXd directSolution(const SystemMatrices& system, const Eigen::VectorXd& rhs) {
  TangentSolver direct(LinearSolverSpec::Method::Cholmod);
  direct.factorize(system);
  return direct.solve(rhs);
}

inline double relativeError(const Eigen::VectorXd& x, const Eigen::VectorXd& reference) {
  return (x - reference).norm() / reference.norm();
}

}  // namespace cc::test
