// Benchmark (not a test): assembly time per thread count and CHOLMOD orderings (fill, flops,
// analysis/factorization/solve time) against UMFPACK on Hex8-mesh sparsity patterns.
// Usage: bench_solver [--assembly-only] [cells per edge ...]  (default 12 18)
#include <cholmod.h>
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

#include "../fem/grid_springs.hpp"
#include "fem/assembler.hpp"
#include "solver/linear_solver.hpp"

namespace {

using cc::FillOrdering;
using Clock = std::chrono::steady_clock;

double seconds(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Process CPU time: on a shared machine the wall time of single-threaded phases is noise.
double cpuSeconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// Bottom layer (z = 0) fixed: the stiffness of the free dofs is positive definite.
cc::DofMap bottomFixed(const cc::test::GridSprings& grid) {
  const Eigen::Matrix3Xd x = grid.referenceMatrix();
  std::vector<bool> constrained(3 * grid.numNodes(), false);
  for (int n = 0; n < grid.numNodes(); ++n) {
    if (x(2, n) == 0) constrained[3 * n] = constrained[3 * n + 1] = constrained[3 * n + 2] = true;
  }
  return cc::DofMap(std::vector<bool>(grid.numNodes(), true), constrained);
}

// Fill and flop count of CHOLMOD's analysis with one ordering (load-independent numbers).
void printFill(const cc::SparseMatrix& matrix, int ordering, const char* name) {
  cholmod_common common;
  cholmod_start(&common);
  common.supernodal = CHOLMOD_SUPERNODAL;
  if (ordering >= 0) {
    common.nmethods = 1;
    common.method[0].ordering = ordering;
  }
  cholmod_sparse view{};
  view.nrow = view.ncol = static_cast<std::size_t>(matrix.rows());
  view.nzmax = static_cast<std::size_t>(matrix.nonZeros());
  view.p = const_cast<int*>(matrix.outerIndexPtr());
  view.i = const_cast<int*>(matrix.innerIndexPtr());
  view.x = const_cast<double*>(matrix.valuePtr());
  view.stype = 1;
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = view.packed = 1;
  cholmod_factor* factor = cholmod_analyze(&view, &common);
  std::printf("  %-18s nnz(L) = %.3e  flops = %.3e\n", name, common.lnz, common.fl);
  cholmod_free_factor(&factor, &common);
  cholmod_finish(&common);
}

void timeSolver(cc::LinearSolver& solver, const cc::SparseMatrix& matrix, const char* name) {
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(matrix.rows());
  double cpu = cpuSeconds();
  solver.analyzePattern(matrix);
  const double analysis = cpuSeconds() - cpu;
  cpu = cpuSeconds();
  solver.factorize(matrix);
  const double factorization = cpuSeconds() - cpu;
  cpu = cpuSeconds();
  const Eigen::VectorXd x = solver.solve(rhs);
  const double solve = cpuSeconds() - cpu;
  std::printf("  %-18s CPU s: analysis %6.2f  factorization %7.2f  solve %5.2f  |Ax-b|/|b| %.1e\n",
              name, analysis, factorization, solve, (matrix * x - rhs).norm() / rhs.norm());
}

void benchmark(int cells, bool assemblyOnly) {
  cc::test::GridSprings grid(cells, cells, cells);
  const cc::DofMap dofs = bottomFixed(grid);
  const Eigen::Matrix3Xd reference = grid.referenceMatrix();
  cc::AssemblyState state;
  state.reference = state.current = state.previous = &reference;
  std::printf("%d^3 Hex8 cells: %d free dofs\n", cells, dofs.numFree());
  cc::SystemMatrices system;
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    cc::Assembler assembler(dofs, {&grid});
    Eigen::VectorXd force;
    cc::SystemMatrices matrices;
    assembler.assemble(state, force, &matrices);  // first call builds coloring and pattern
    const auto start = Clock::now();
    const double cpu = cpuSeconds();
    constexpr int kRepeats = 3;
    for (int k = 0; k < kRepeats; ++k) assembler.assemble(state, force, &matrices);
    std::printf(
        "  assembly, %d thread(s): wall %.3f s, CPU %.3f s (pattern + coloring once: "
        "%.3f s), nnz(K_ff) = %ld\n",
        threads, seconds(start) / kRepeats, (cpuSeconds() - cpu) / kRepeats,
        assembler.timings().pattern, static_cast<long>(matrices.free.nonZeros()));
    system = std::move(matrices);
  }
  if (assemblyOnly) return;
  printFill(system.free, CHOLMOD_AMD, "AMD");
  printFill(system.free, CHOLMOD_METIS, "METIS");
  printFill(system.free, CHOLMOD_NESDIS, "NESDIS");
  printFill(system.free, -1, "automatic");
  const std::pair<FillOrdering, const char*> orderings[] = {
      {FillOrdering::Amd, "CHOLMOD AMD"},
      {FillOrdering::Metis, "CHOLMOD METIS"},
      {FillOrdering::NestedDissection, "CHOLMOD NESDIS"},
      {FillOrdering::Automatic, "CHOLMOD automatic"}};
  for (const auto& [ordering, name] : orderings) {
    auto solver = cc::makeCholmodSolver(ordering);
    timeSolver(*solver, system.free, name);
  }
  for (const auto& [ordering, name] : {std::pair{FillOrdering::Amd, "UMFPACK AMD"},
                                       std::pair{FillOrdering::Metis, "UMFPACK METIS"}}) {
    auto solver = cc::makeUmfpackSolver(ordering);
    timeSolver(*solver, system.free, name);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  bool assemblyOnly = false;
  for (int k = 1; k < argc; ++k) {
    if (std::string(argv[k]) == "--assembly-only") {
      assemblyOnly = true;
    } else {
      sizes.push_back(std::atoi(argv[k]));
    }
  }
  if (sizes.empty()) sizes = {12, 18};
  for (int cells : sizes) benchmark(cells, assemblyOnly);
}
