// LinearSolver: the sparse solver behind Newton's method. CHOLMOD serves symmetric systems,
// UMFPACK unsymmetric ones; the PETSc backend (solver/petsc_solver.cpp) implements the same
// interface with MUMPS, SuperLU_dist (direct) and GMRES with hypre BoomerAMG or GAMG
// (iterative). The symbolic analysis is redone only when the sparsity pattern changes.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

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
  // Size of the largest numeric factor so far (values and indices; L for CHOLMOD, L and U for
  // UMFPACK): the memory a run cannot do without (benchmarks compare peak memory against it).
  double largestFactorBytes = 0;
  // Floating-point operations of the most expensive factorization so far (CHOLMOD: counted by
  // its analysis; UMFPACK: by the factorization): a cost measure that does not depend on the
  // machine's load, for comparing orderings.
  double largestFactorFlops = 0;
  // Iterative backends: Krylov iterations summed over solves, and solves that stalled or
  // diverged and were redone with a direct solver (TangentSolver's fallback).
  long krylovIterations = 0;
  int krylovFallbacks = 0;
  // factorize() calls that kept an earlier preconditioner: the AMG hierarchy of an iterative
  // backend (petsc_solver.cpp), or the factor of a direct one (factor_reuse.hpp).
  int reusedPreconditioners = 0;
  // Analyses that kept the fill-reducing ordering of an earlier pattern of the same size
  // (CHOLMOD and UMFPACK: a contact pattern differs from the last by a few couplings).
  int reusedOrderings = 0;
  // UMFPACK: times a factorization grew its workspace (from the compact start of a large
  // system, umfpackInitialAllocation).
  int workspaceGrowths = 0;
  // UMFPACK: refined solves whose factor alone left a residual that called for a refinement step.
  int refinementSteps = 0;
  // Several processes: bytes this process sent for matrix entries of rows another process
  // owns, and received of the solution (the direct solver's own traffic is not counted).
  double matrixBytesSent = 0;
  double solutionBytesReceived = 0;

  LinearSolverStatistics& operator+=(const LinearSolverStatistics& other);
};

// Smallest over largest pivot (of D in A = L D L^T, or of U) below which the matrix counts as
// singular. An exactly singular matrix (a free rigid-body mode, a missing support) shows a
// round-off pivot of order n * eps relative to the largest (2e-15 for a 41-dof free chain);
// a genuine system this ill-conditioned (cond > 1e13) leaves under three correct digits in a
// solve, so rejecting it loses nothing that Newton could use.
inline constexpr double kSingularPivotRatio = 1e-13;

// Where the free equations sit in the mesh. An iterative backend builds from it the 3-dof node
// blocks (hypre's nodal coarsening) and the near-nullspace of the rigid-body modes (AMG
// interpolation); direct backends do not need it.
// On several processes the matrix each process passes holds its share only (the system is the
// sum of the shares, see NonlinearProblem) and right-hand sides are whole on every process;
// rows are distributed by nodeOwner.
struct SystemLayout {
  std::vector<int> freeDofs;     // equation -> nodal dof 3 * node + component, ascending
  Eigen::Matrix3Xd coordinates;  // current nodal coordinates (all nodes)
  std::vector<int> nodeOwner;    // process owning each node; empty on one process
};

// Krylov iterations before a solve counts as stalled (the caller then falls back to a direct
// solve). BoomerAMG-GMRES needs 10-40 on the tangents measured (docs/performance/solvers.md).
inline constexpr int kKrylovIterationLimit = 400;

// A Krylov solve that stalled or diverged: the caller redoes the solve with a direct solver.
class KrylovFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A Krylov solve left because the run was asked to stop (SIGINT/SIGTERM, LinearSolver::
// setStopPoll): the iteration is abandoned; no other solver redoes it.
class SolveInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The last solve of an iterative backend.
struct KrylovReport {
  int iterations = 0;
  double relativeResidual = 0;  // ||b - A x|| / ||b|| reached (preconditioned for GMRES)
  std::string reason;           // PETSc's KSPConvergedReason, spelled out
};

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
  // The factor alone applied to rhs, without refinement against the factorized matrix: the
  // preconditioner of a later tangent (factor_reuse.hpp), after the matrix passed to
  // factorize() may have been overwritten, or given another pattern, by that tangent.
  virtual Eigen::VectorXd applyFactor(const Eigen::VectorXd& rhs) { return solve(rhs); }
  // Frees the numeric factor and keeps the symbolic analysis: a solver that another one has
  // replaced for now (CHOLMOD while the system is unsymmetric) holds no factor memory.
  virtual void releaseFactor() = 0;
  // The sign (+1, -1, 0) of the determinant of the matrix last factorized, where the backend
  // can tell it from its factor (UMFPACK), else nothing.
  virtual std::optional<int> determinantSign() { return std::nullopt; }

  // Iterative backends only (direct ones ignore these): the relative residual the next solves
  // must reach (Newton's forcing term), the mesh layout of the equations, the last solve.
  virtual bool iterative() const { return false; }
  virtual void setRelativeTolerance(double) {}
  // Krylov iterations after which a solve counts as stalled (default kKrylovIterationLimit;
  // TangentSolver holds GAMG to a convergence rate with it, a test forces the fallback).
  virtual void setIterationLimit(int) {}
  virtual void setLayout(const SystemLayout&) {}
  virtual KrylovReport lastSolve() const { return {}; }
  // Asked between Krylov iterations whether the run is to stop; true ends the solve with
  // SolveInterrupted. Called on every process in step (a collective poll may reduce); it must
  // not throw (PETSc calls it).
  virtual void setStopPoll(std::function<bool()>) {}
  // Rows per block of the matrix the backend solves: 3 where an iterative backend sees the
  // mesh's node blocks (SystemLayout), else 1.
  virtual int matrixBlockSize() const { return 1; }

  const LinearSolverStatistics& statistics() const { return statistics_; }

 protected:
  LinearSolverStatistics statistics_;
};

// Fill-reducing ordering of the symbolic analysis.
enum class FillOrdering {
  Amd,               // approximate minimum degree (UMFPACK: AMD or COLAMD)
  Metis,             // METIS nested dissection
  NestedDissection,  // CHOLMOD's NESDIS (METIS + constrained minimum degree); CHOLMOD only
  Automatic,         // AMD, METIS tried as well when AMD's fill is high
};
// Measured with tests/unit/solver/bench_solver on Hex8-mesh patterns (18^3 cells, 19494 dofs,
// CPU seconds with the reference BLAS): CHOLMOD nnz(L) / flops / factorization AMD 1.31e7 /
// 1.75e10 / 9.1 s, METIS 8.7e6 / 6.6e9 / 2.6 s, NESDIS 8.8e6 / 6.7e9 / 2.5 s; Automatic
// reaches METIS's fill after running AMD as well. METIS and NESDIS tie on that cube; METIS is
// the default for UMFPACK (it has no NESDIS).
inline constexpr FillOrdering kDefaultOrdering = FillOrdering::Metis;
// CHOLMOD's default. On the tangents of example 6.1 refined to 57 k - 200 k free dofs (contact
// included; scripts/bench.py, docs/performance/README.md) NESDIS needs 3-5% fewer flops and a
// 5-7% smaller factor than METIS at every size (200 k: 77.3 vs 79.9 GFlop, 772 vs 818 MiB;
// AMD 150 GFlop), at no extra analysis time.
inline constexpr FillOrdering kDefaultCholmodOrdering = FillOrdering::NestedDissection;

std::unique_ptr<LinearSolver> makeCholmodSolver(FillOrdering ordering = kDefaultCholmodOrdering);
// Throws std::invalid_argument for NestedDissection.
std::unique_ptr<LinearSolver> makeUmfpackSolver(FillOrdering ordering = kDefaultOrdering);
// The same with the size, in UMFPACK's memory units, beyond which a factorization moves from
// 32-bit to 64-bit indices (tests lower it to reach the 64-bit routines on small systems).
std::unique_ptr<LinearSolver> makeUmfpackSolver(FillOrdering ordering, double narrowUnitLimit);
// And with the size from which a factorization starts from a compact workspace (tests lower it).
std::unique_ptr<LinearSolver> makeUmfpackSolver(FillOrdering ordering, double narrowUnitLimit,
                                                Eigen::Index compactWorkspaceFrom);

// UMFPACK keeps the factor (L, U) at the bottom of one workspace and its working data (the
// matrix's entries, the fronts' contributions) at the top, meeting in the middle. Its default
// first workspace is sized from the analysis's estimate, a loose upper bound (9.0 GiB for a
// 1.35 GiB factor at 232 k equations, capped near 2 GiB), so the two ends touch separate pages
// and the process holds the factor plus the largest extent of the working data (1.84 GiB for
// that 1.35 GiB factor). Started compact, the workspace grows as the factor does (UMFPACK moves
// the working data up at each growth) and the two share pages: 1.63 GiB there, the
// factorization as fast (docs/performance/solvers.md, eighteenth session). From
// kMemoryBoundSystemFrom equations a factorization starts compact; smaller systems keep the
// default, which grows less often.
//
// The size from which memory, not the allocations' cost, limits a direct solve: where
// solver=auto leaves the direct solvers (kIterativeBreakEven, measured), UMFPACK starts its
// workspace compact and the engine's heap returns freed memory (app/heap_policy.hpp).
inline constexpr Eigen::Index kMemoryBoundSystemFrom = 50000;
// Fraction of the analysis's factor estimate a compact workspace starts with.
inline constexpr double kCompactUmfpackWorkspace = 0.1;
// The value of UMFPACK's control UMFPACK_ALLOC_INIT for a system of `equations` whose analysis
// estimated the factor at `factorEstimateUnits` of UMFPACK's memory units: its default (0.7:
// a fraction of the estimate) below `compactFrom`, from there minus the compact start in units
// (a negative value is a size).
double umfpackInitialAllocation(Eigen::Index equations, double factorEstimateUnits,
                                Eigen::Index compactFrom = kMemoryBoundSystemFrom);

// Makes the BLAS library take its work buffer now, once per process, or throws OutOfMemory if
// the address space left cannot hold it (OpenBLAS retries a failed allocation of that buffer
// forever: a hang under `ulimit -v`). CHOLMOD and UMFPACK call it before their first analysis.
void reserveBlasWorkspace();

// PETSc backends (solver/petsc_solver.cpp; PETSc and MPI are initialized on first use).
enum class PetscMethod { Mumps, SuperluDist, BoomerAmg, Gamg };
std::unique_ptr<LinearSolver> makePetscSolver(PetscMethod method);

}  // namespace cc
