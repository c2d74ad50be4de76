// PETSc behind the LinearSolver interface (issue 13): MUMPS and SuperLU_dist LU (direct), and
// right-preconditioned GMRES with hypre BoomerAMG or PETSc's GAMG (iterative). Built as the
// plugin covcontact_petsc, which solver/petsc_loader.cpp loads on first use: a run that never
// uses PETSc does not pay for loading its ~50 libraries (+75 ms of dynamic linking at start-up,
// measured) nor for starting MPI.
//
// The system. Direct backends factor K_ff as it is. Iterative backends solve the same system
// embedded in all 3 * numNodes nodal dofs: every dof that is not free (prescribed, inactive)
// gets an identity row and column scaled by the mean |diagonal| of K_ff, with zero right-hand
// side, so the free part of the solution is exactly K_ff^-1 b. The embedding gives the matrix
// a block size of 3 (hypre's nodal coarsening and vector interpolation, GAMG's aggregation of
// nodes) and lets PETSc build the six rigid-body modes of the mesh as the near-nullspace
// (MatNullSpaceCreateRigidBody on the current coordinates).
//
// Distribution (issue 17). On one process the rows are the equations (or nodal dofs, embedded)
// in their order and the matrix is MATAIJ = SeqAIJ with exactly the CSR structure of K, whose
// value array setValues fills in place. On several processes (SystemLayout::nodeOwner) the rows
// are renumbered so that each process owns a contiguous range holding the dofs of its nodes
// (MATMPIAIJ); each process's pattern holds its own rows complete, which become its local
// rows in place (MatCreateMPIAIJWithSplitArrays once per pattern, values written into them per
// tangent, and the nonzeros of other processes' rows added through PETSc's stash), sets the
// right-hand side rows it owns, and receives the whole solution (VecScatterCreateToAll), so
// that Newton goes on identically on every process.
#include <fmt/format.h>
#include <omp.h>
#include <petscksp.h>

#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/errors.hpp"
#include "common/stopwatch.hpp"
#include "parallel/petsc_runtime.hpp"
#include "solver/linear_solver.hpp"

namespace cc {

namespace {

// SuperLU_dist 8.1 as Debian builds it parallelizes its factorization with OpenMP, and that
// path races: on the 5 x 5 x 5 lattice of test_petsc_solver.cpp 2 of 25 factorizations with
// two threads had a relative residual of 0.16-0.21 (0 of 25 with one thread). Its set-up and
// solves therefore run with one OpenMP thread.
class OneOpenMpThread {
 public:
  explicit OneOpenMpThread(bool active) : saved_(active ? omp_get_max_threads() : 0) {
    if (saved_ > 0) omp_set_num_threads(1);
  }
  ~OneOpenMpThread() {
    if (saved_ > 0) omp_set_num_threads(saved_);
  }
  OneOpenMpThread(const OneOpenMpThread&) = delete;
  OneOpenMpThread& operator=(const OneOpenMpThread&) = delete;

 private:
  int saved_;
};

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(fmt::format("PETSc: {} failed (error {})", what, code));
}

constexpr PetscInt kGmresRestart = 100;
// A lagged AMG hierarchy: the set-up (aggregation, smoothed prolongation, Galerkin products) is
// half of the linear solver's time (GAMG, 57 k scaling deck on 2 processes: 7.0 s of 13.4 s),
// while one hierarchy preconditions the tangents of several Newton iterations nearly as well
// (GMRES then sees the current matrix; only the preconditioner is older, so every solve still
// reaches its forcing tolerance and Newton's iterations are unchanged). The hierarchy is rebuilt
// when a solve's convergence rate, -log10(achieved relative residual) per Krylov iteration,
// falls below kLaggedRateRatio times the rate of the first solve after the last rebuild (a
// rate, not an iteration count: Newton's forcing term asks for 1e-3 in one solve and 1e-10 a
// few later), after a stalled solve, and with every new pattern. The PETSc option
// -cc_hierarchy_rate_ratio overrides the ratio (1 or more: a new hierarchy for every tangent, as
// before; for benchmarks).
constexpr double kLaggedRateRatio = 0.7;
// Relative residual above which a direct solve counts as failed (round-off of a backward-stable
// LU is ~1e-15 on our tangents; SuperLU_dist's static pivoting can miss by far more). The PETSc
// option -cc_direct_residual overrides it (tests: below round-off, every direct solve misses).
constexpr double kDirectResidual = 1e-8;
// ... unless the solve is backward stable and its residual still makes a Newton step. A
// backward-stable solve leaves ||b - K x|| ~ eps (||K|| ||x|| + ||b||), which on a nearly
// singular tangent lies far above eps ||b||: the thin strip held only by viscous stabilisation
// (SingularSystem.ThinStrip*) on 2 processes had MUMPS solves at 2.7e-7 of ||b|| with a
// normwise backward error of 1.0e-16, the whole round-off of double precision, and stopped as
// singular where the serial run completes. No other direct solver would do better on several
// processes. Such a solve is accepted if its normwise backward error
// ||r||_inf / (||K||_inf ||x||_inf + ||b||_inf) is below kDirectBackwardError (measured 2e-17 to
// 2e-16; a failed pivoting is far above) and its relative residual below kDirectUsableResidual,
// the loosest forcing term Newton asks of an iterative solve (kForcingMax, solver/newton.hpp):
// the tangent of a free rigid-body motion, solved just as stably, leaves a relative residual
// above 1 (6.3 on the strip's first step) and still counts as singular. The PETSc option
// -cc_direct_backward_error overrides the first (tests: 0 makes every miss count).
constexpr double kDirectBackwardError = 1e-12;
constexpr double kDirectUsableResidual = 1e-3;
// The largest margin of MUMPS's work arrays beyond the analysis's estimate (ICNTL(14), per
// cent; MUMPS's default is 20 to 35 by matrix type) that the retries of factorize() go to.
constexpr PetscInt kMaxMumpsMargin = 320;

const char* methodName(PetscMethod method) {
  switch (method) {
    case PetscMethod::Mumps:
      return "MUMPS";
    case PetscMethod::SuperluDist:
      return "SuperLU_dist";
    case PetscMethod::BoomerAmg:
      return "GMRES+BoomerAMG";
    case PetscMethod::Gamg:
      return "GMRES+GAMG";
  }
  return "?";
}

class PetscSolver final : public LinearSolver {
 public:
  explicit PetscSolver(PetscMethod method) : method_(method) {
    petsc::ensureInitialized();
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank_);
    MPI_Comm_size(PETSC_COMM_WORLD, &processes_);
  }
  ~PetscSolver() override { destroy(); }
  PetscSolver(const PetscSolver&) = delete;
  PetscSolver& operator=(const PetscSolver&) = delete;

  std::string name() const override { return methodName(method_); }
  bool iterative() const override {
    return method_ == PetscMethod::BoomerAmg || method_ == PetscMethod::Gamg;
  }
  void setRelativeTolerance(double tolerance) override { relativeTolerance_ = tolerance; }
  void setIterationLimit(int iterations) override { maxIterations_ = iterations; }
  void setLayout(const SystemLayout& layout) override { layout_ = layout; }
  void setStopPoll(std::function<bool()> poll) override { stopPoll_ = std::move(poll); }
  KrylovReport lastSolve() const override { return last_; }
  // MUMPS: from the last factorization (ICNTL 33); the other backends cannot tell.
  std::optional<int> determinantSign() override { return determinantSign_; }
  int matrixBlockSize() const override {
    PetscInt blockSize = 1;
    if (matrix_) check(MatGetBlockSize(matrix_, &blockSize), "MatGetBlockSize");
    return static_cast<int>(blockSize);
  }

  void analyzePattern(const SparseMatrix& matrix) override {
    if (!matrix.isCompressed() || matrix.rows() != matrix.cols()) {
      throw std::invalid_argument("PETSc: matrix must be square and compressed");
    }
    const auto start = std::chrono::steady_clock::now();
    destroy();
    if (layout_.nodeOwner.empty()) {
      buildStructure(matrix);
      createMatrix();
    } else {
      createDistributedMatrix(matrix);
    }
    createVectors();
    createSolver();
    ++statistics_.analyses;
    statistics_.analysisSeconds += secondsSince(start);
  }

  void factorize(const SparseMatrix& matrix) override {
    if (!matrix_ || matrix.rows() != equations_ || matrix.nonZeros() != nonZeros_) {
      throw std::logic_error("PETSc: factorize() before analyzePattern() of this pattern");
    }
    const auto start = std::chrono::steady_clock::now();
    ++statistics_.factorizations;
    factored_ = false;
    determinantSign_.reset();
    setValues(matrix);
    const bool reuseHierarchy = iterative() && hierarchyBuilt_ && !rebuildHierarchy_;
    if (iterative()) {
      setNearNullSpace();
      check(KSPSetReusePreconditioner(ksp_, reuseHierarchy ? PETSC_TRUE : PETSC_FALSE),
            "KSPSetReusePreconditioner");
    }
    // MUMPS sizes its work arrays from the analysis's estimate plus ICNTL(14) per cent; pivoting
    // can need more than that (INFOG(1) = -8, -9, -11 .. -15). Then the factorization is redone
    // with twice the margin, as MUMPS's manual advises, up to kMaxMumpsMargin per cent.
    PetscInt margin = 0;  // MUMPS's default
    for (;;) {
      if (factorOnce(matrix, margin) == FactorOutcome::Done) break;
      margin = std::max<PetscInt>(2 * lastMumpsMargin_, 20);
      if (margin > kMaxMumpsMargin) {
        throw OutOfMemory(fmt::format(
            "MUMPS's work arrays were still too small for the LU factor of the {} x {} tangent "
            "({} nonzeros) with {} % beyond the analysis's estimate of {}: pivoting fills "
            "this factor far beyond its structure; try solver=umfpack",
            matrix.rows(), matrix.cols(), matrix.nonZeros(), lastMumpsMargin_, estimateText()));
      }
      ++statistics_.failedFactorizations;
      releaseFactor();
    }
    statistics_.factorizationSeconds += secondsSince(start);
    factored_ = true;
    if (factor_ && method_ == PetscMethod::Mumps) {
      // det = RINFOG(12) * 2^INFOG(34) (real arithmetic), the same on every process.
      PetscReal mantissa = 0;
      check(MatMumpsGetRinfog(factor_, 12, &mantissa), "MatMumpsGetRinfog");
      determinantSign_ = mantissa > 0 ? 1 : mantissa < 0 ? -1 : 0;
    }
    if (iterative()) {
      if (reuseHierarchy) {
        ++statistics_.reusedPreconditioners;
      } else {
        hierarchyBuilt_ = true;
        rebuildHierarchy_ = false;
        rateAfterRebuild_ = -1;  // measured by the next solve
      }
    }
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    if (!factored_) throw std::logic_error("PETSc: solve() without factorization");
    const auto start = std::chrono::steady_clock::now();
    PetscScalar* values = nullptr;
    check(VecSet(rhs_, 0.0), "VecSet");
    check(VecGetArray(rhs_, &values), "VecGetArray");
    const auto [first, last] = ownedRows();
    for (Eigen::Index e = 0; e < equations_; ++e) {
      if (row_[e] >= first && row_[e] < last) values[row_[e] - first] = rhs[e];
    }
    check(VecRestoreArray(rhs_, &values), "VecRestoreArray");
    if (iterative()) {
      check(KSPSetTolerances(ksp_, relativeTolerance_, 0.0, 1e5, maxIterations_),
            "KSPSetTolerances");
    }
    stopped_ = false;
    {
      const OneOpenMpThread oneThread(method_ == PetscMethod::SuperluDist);
      check(KSPSolve(ksp_, rhs_, solution_), "KSPSolve");
    }
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    check(KSPGetConvergedReason(ksp_, &reason), "KSPGetConvergedReason");
    PetscInt iterations = 0;
    check(KSPGetIterationNumber(ksp_, &iterations), "KSPGetIterationNumber");
    last_.iterations = static_cast<int>(iterations);
    last_.reason = KSPConvergedReasons[reason];
    last_.relativeResidual = trueRelativeResidual();
    statistics_.krylovIterations += iterations;
    statistics_.solveSeconds += secondsSince(start);
    ++statistics_.solves;
    if (stopped_) {
      throw SolveInterrupted(
          fmt::format("{}: stopped on request after {} Krylov iterations", name(), iterations));
    }
    // A direct solve whose residual is far above round-off did not solve the system.
    if (!iterative() && !(last_.relativeResidual <= directResidual_) && !solvedToRoundOff())
      reason = KSP_DIVERGED_BREAKDOWN;
    if (iterative()) judgeHierarchy(reason, iterations);
    if (reason < 0) {
      throw KrylovFailure(fmt::format(
          "{}: {} after {} iterations (relative residual {:.3g}, "
          "asked {:.3g})",
          name(), last_.reason, iterations, last_.relativeResidual, relativeTolerance_));
    }
    // The whole solution on every process (on one process the solution vector is whole).
    Vec whole = solution_;
    if (distributed_) {
      check(VecScatterBegin(toAll_, solution_, all_, INSERT_VALUES, SCATTER_FORWARD),
            "VecScatterBegin");
      check(VecScatterEnd(toAll_, solution_, all_, INSERT_VALUES, SCATTER_FORWARD),
            "VecScatterEnd");
      whole = all_;
      statistics_.solutionBytesReceived +=
          static_cast<double>(size_ - (last - first)) * sizeof(PetscScalar);
    }
    Eigen::VectorXd result(equations_);
    const PetscScalar* x = nullptr;
    check(VecGetArrayRead(whole, &x), "VecGetArrayRead");
    for (Eigen::Index e = 0; e < equations_; ++e) result[e] = x[row_[e]];
    check(VecRestoreArrayRead(whole, &x), "VecRestoreArrayRead");
    return result;
  }

  void releaseFactor() override {
    // The factor (direct) or hierarchy (AMG) lives in the PC; a reset frees it, the matrix and
    // its structure stay for the next factorize().
    if (ksp_) {
      KSPReset(ksp_);
      createSolverSettings();
    }
    factored_ = false;
    determinantSign_.reset();
    hierarchyBuilt_ = false;
  }

 private:
  // Whether the next factorize() rebuilds the AMG hierarchy (kLaggedRateRatio). The same
  // decision on every process: the iteration count and residual are global.
  void judgeHierarchy(KSPConvergedReason reason, PetscInt iterations) {
    if (reason < 0) {
      rebuildHierarchy_ = true;
      return;
    }
    const double ratio = laggedRateRatio_;
    if (ratio >= 1) {
      rebuildHierarchy_ = true;  // no lag
      return;
    }
    if (iterations <= 0 || !(last_.relativeResidual > 0)) return;
    const double rate = -std::log10(last_.relativeResidual) / static_cast<double>(iterations);
    if (rateAfterRebuild_ < 0) {
      rateAfterRebuild_ = rate;
    } else if (rate < ratio * rateAfterRebuild_) {
      rebuildHierarchy_ = true;
    }
  }

  enum class FactorOutcome { Done, WorkspaceTooSmall };

  // One numeric factorization (direct) or AMG set-up (iterative) of the values set. Throws
  // OutOfMemory when memory ran out, StepFailure for a singular tangent.
  FactorOutcome factorOnce(const SparseMatrix& matrix, int mumpsMargin) {
    check(KSPSetOperators(ksp_, matrix_, matrix_), "KSPSetOperators");
    PC pc = nullptr;
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    factor_ = nullptr;
    if (method_ == PetscMethod::Mumps) {
      // Null-pivot detection (ICNTL 24) with the threshold of the other direct solvers
      // (CNTL 3 relative to ||A||): without it MUMPS factors a singular tangent silently.
      check(PCFactorSetUpMatSolverType(pc), "PCFactorSetUpMatSolverType");
      check(PCFactorGetMatrix(pc, &factor_), "PCFactorGetMatrix");
      check(MatMumpsSetIcntl(factor_, 24, 1), "MatMumpsSetIcntl");
      if (mumpsMargin > 0) check(MatMumpsSetIcntl(factor_, 14, mumpsMargin), "MatMumpsSetIcntl");
      check(MatMumpsGetIcntl(factor_, 14, &lastMumpsMargin_), "MatMumpsGetIcntl");
      check(MatMumpsSetCntl(factor_, 3, kSingularPivotRatio), "MatMumpsSetCntl");
      // The determinant as a by-product of the factorization (ICNTL 33): its sign serves the
      // fold verdict of a failing Newton solve (solver/tangent_orientation.hpp) on models too
      // large, or too distributed, for that watch to factorize copies of its own.
      check(MatMumpsSetIcntl(factor_, 33, 1), "MatMumpsSetIcntl");
    }
    // Direct: the analysis and numeric factorization; iterative: the AMG hierarchy.
    const OneOpenMpThread oneThread(method_ == PetscMethod::SuperluDist);
    const PetscErrorCode code = KSPSetUp(ksp_);
    if (code == PETSC_ERR_MEM) {
      throw OutOfMemory(fmt::format(
          "{} ran out of memory setting up the {} x {} tangent ({} nonzeros): {} of this model "
          "does not fit; use fewer elements or a machine with more memory",
          name(), matrix.rows(), matrix.cols(), matrix.nonZeros(),
          iterative() ? "the multigrid hierarchy" : "the LU factor"));
    }
    PCFailedReason reason = PC_NOERROR;
    check(PCGetFailedReason(pc, &reason), "PCGetFailedReason");
    if (factor_ && reason == PC_FACTOR_OUTMEMORY) {
      PetscInt status = 0;  // INFOG(1): the same on every process
      check(MatMumpsGetInfog(factor_, 1, &status), "MatMumpsGetInfog");
      if (status != -13 && status != -5 && status != -7) return FactorOutcome::WorkspaceTooSmall;
      throwMumpsOutOfMemory(matrix, status);
    }
    PetscInt nullPivots = 0;
    if (factor_ && code == 0) check(MatMumpsGetInfog(factor_, 28, &nullPivots), "MatMumpsGetInfog");
    if (nullPivots > 0) reason = PC_FACTOR_NUMERIC_ZEROPIVOT;
    if (code != 0 || reason != PC_NOERROR) {
      ++statistics_.failedFactorizations;
      throw StepFailure(FailureKind::SingularSystem,
                        fmt::format("{}: factorization failed ({}; a body free to move as a "
                                    "rigid body, or a missing support?)",
                                    name(), code != 0 ? "error" : PCFailedReasons[reason]));
    }
    return FactorOutcome::Done;
  }

  // MUMPS could not allocate (INFOG(1) = -13 in the factorization, -5 or -7 in the analysis):
  // INFO(2) is the number of reals it asked for (times 1e6 when negative), on this process.
  [[noreturn]] void throwMumpsOutOfMemory(const SparseMatrix& matrix, PetscInt status) {
    PetscInt asked = 0;
    check(MatMumpsGetInfo(factor_, 2, &asked), "MatMumpsGetInfo");
    const double bytes =
        (asked < 0 ? -1e6 * static_cast<double>(asked) : static_cast<double>(asked)) *
        sizeof(PetscScalar);
    const std::string request =
        asked != 0 ? fmt::format(" (an allocation of {:.1f} MiB failed)", bytes / (1 << 20))
                   : std::string();
    throw OutOfMemory(fmt::format(
        "MUMPS ran out of memory in the {} of the {} x {} tangent ({} nonzeros){}; the analysis "
        "estimated {}: the LU factor of this model does not fit; use fewer elements or a "
        "machine with more memory",
        status == -13 ? "factorization" : "analysis", matrix.rows(), matrix.cols(),
        matrix.nonZeros(), request, estimateText()));
  }

  // INFOG(17): the analysis's estimate of MUMPS's memory for the factorization, in MB, summed
  // over the processes.
  std::string estimateText() const {
    PetscInt megabytes = 0;
    if (!factor_ || MatMumpsGetInfog(factor_, 17, &megabytes) != 0 || megabytes <= 0) {
      return "nothing (it did not finish)";
    }
    return fmt::format("{:.2f} GiB for the factorization", megabytes * 1e6 / (1 << 30));
  }

  // The rows this process owns.
  std::pair<PetscInt, PetscInt> ownedRows() const {
    return {firstRow_[static_cast<std::size_t>(rank_)],
            firstRow_[static_cast<std::size_t>(rank_) + 1]};
  }
  bool ownsRow(PetscInt r) const {
    const auto [first, last] = ownedRows();
    return r >= first && r < last;
  }

  // PETSc row of every equation (row_), the first row of every process (firstRow_) and, for
  // the embedded system, the nodal dof of every row (dofOfRow_). On several processes the rows
  // of process p are the dofs of the nodes it owns, node by node (block size 3 kept).
  void numberRows(bool embed) {
    const std::size_t nodes = static_cast<std::size_t>(layout_.coordinates.cols());
    distributed_ = !layout_.nodeOwner.empty();
    if (distributed_ && (layout_.nodeOwner.size() != nodes ||
                         static_cast<Eigen::Index>(layout_.freeDofs.size()) != equations_)) {
      throw std::invalid_argument("PETSc: SystemLayout does not fit the distributed system");
    }
    firstRow_.assign(static_cast<std::size_t>(processes_) + 1, size_);
    firstRow_[0] = 0;
    if (!distributed_) {
      firstRow_.assign({0, size_});
      for (Eigen::Index e = 0; e < equations_; ++e) {
        row_[e] = embed ? layout_.freeDofs[static_cast<std::size_t>(e)] : static_cast<PetscInt>(e);
        if (e > 0 && row_[e] <= row_[e - 1]) {
          throw std::invalid_argument("PETSc: SystemLayout::freeDofs must ascend");
        }
      }
      dofOfRow_.resize(embed ? static_cast<std::size_t>(size_) : 0);
      for (std::size_t r = 0; r < dofOfRow_.size(); ++r) dofOfRow_[r] = static_cast<PetscInt>(r);
      return;
    }
    constexpr PetscInt kNotARow = -1, kUnnumbered = -2;
    std::vector<PetscInt> rowOfDof(3 * nodes, embed ? kUnnumbered : kNotARow);
    for (int dof : layout_.freeDofs) rowOfDof[static_cast<std::size_t>(dof)] = kUnnumbered;
    std::vector<std::vector<int>> nodesOf(static_cast<std::size_t>(processes_));
    for (std::size_t n = 0; n < nodes; ++n) {
      nodesOf[static_cast<std::size_t>(layout_.nodeOwner[n])].push_back(static_cast<int>(n));
    }
    PetscInt next = 0;
    dofOfRow_.assign(static_cast<std::size_t>(size_), 0);
    for (int p = 0; p < processes_; ++p) {
      firstRow_[static_cast<std::size_t>(p)] = next;
      for (int node : nodesOf[static_cast<std::size_t>(p)]) {
        for (int c = 0; c < 3; ++c) {
          PetscInt& row = rowOfDof[static_cast<std::size_t>(3 * node + c)];
          if (row != kUnnumbered) continue;
          dofOfRow_[static_cast<std::size_t>(next)] = 3 * node + c;
          row = next++;
        }
      }
    }
    firstRow_[static_cast<std::size_t>(processes_)] = next;
    for (Eigen::Index e = 0; e < equations_; ++e) {
      row_[e] = rowOfDof[static_cast<std::size_t>(layout_.freeDofs[static_cast<std::size_t>(e)])];
    }
  }

  // One process: the CSR of the whole (embedded) system in PETSc's row numbering (buildRows).
  void buildStructure(const SparseMatrix& matrix) {
    numberSystem(matrix);
    buildRows(matrix, [](PetscInt) { return true; });
  }

  // The system's size (embedded or not), the PETSc row of every equation and the identity rows
  // of the embedding this process owns.
  void numberSystem(const SparseMatrix& matrix) {
    equations_ = matrix.rows();
    nonZeros_ = matrix.nonZeros();
    embedded_ = iterative() && static_cast<Eigen::Index>(layout_.freeDofs.size()) == equations_ &&
                layout_.coordinates.cols() > 0;
    size_ = embedded_ ? static_cast<PetscInt>(3 * layout_.coordinates.cols())
                      : static_cast<PetscInt>(equations_);
    row_.resize(static_cast<std::size_t>(equations_));
    numberRows(embedded_);
    identityRows_.clear();
    if (!embedded_) return;
    std::vector<char> isFree(static_cast<std::size_t>(size_), 0);
    for (PetscInt r : row_) isFree[static_cast<std::size_t>(r)] = 1;
    const auto [first, last] = ownedRows();
    for (PetscInt r = first; r < last; ++r) {
      if (!isFree[static_cast<std::size_t>(r)]) identityRows_.push_back(r);
    }
  }

  // The rows of the (embedded) system that `keep` accepts, in PETSc's numbering, as CSR from K's
  // column-major storage (CSR of K = CSC of K^T; K is not symmetric in general): rowStart_,
  // columns_ ascending in every row, position_ (where each entry of K's storage goes; -1: in a
  // row not kept) and identitySlots_ (the one entry of each identity row, identityRows_). A
  // counting sort: the rows' lengths, then the columns visited in PETSc's order.
  template <typename Keep>
  void buildRows(const SparseMatrix& matrix, Keep keep) {
    const int* starts = matrix.outerIndexPtr();
    const int* inner = matrix.innerIndexPtr();
    std::vector<PetscCount> next(static_cast<std::size_t>(size_) + 1, 0);
    for (Eigen::Index k = 0; k < nonZeros_; ++k) {
      const PetscInt r = row_[inner[k]];
      if (keep(r)) ++next[static_cast<std::size_t>(r) + 1];
    }
    for (PetscInt r : identityRows_) ++next[static_cast<std::size_t>(r) + 1];
    for (std::size_t r = 0; r < static_cast<std::size_t>(size_); ++r) next[r + 1] += next[r];
    if (next.back() > std::numeric_limits<PetscInt>::max()) {
      throw OutOfMemory(
          fmt::format("PETSc: {} matrix entries on one process exceed PETSc's {}-bit "
                      "indices; run on more processes",
                      next.back(), 8 * sizeof(PetscInt)));
    }
    rowStart_.assign(next.begin(), next.end());
    columns_.assign(static_cast<std::size_t>(next.back()), 0);
    position_.assign(static_cast<std::size_t>(nonZeros_), -1);
    identitySlots_.clear();
    for (PetscInt r : identityRows_) {
      identitySlots_.push_back(next[static_cast<std::size_t>(r)]);
      columns_[static_cast<std::size_t>(next[static_cast<std::size_t>(r)]++)] = r;
    }
    std::vector<Eigen::Index> equationOfRow(static_cast<std::size_t>(size_), -1);
    for (Eigen::Index e = 0; e < equations_; ++e) equationOfRow[row_[e]] = e;
    for (PetscInt c = 0; c < size_; ++c) {
      const Eigen::Index j = equationOfRow[static_cast<std::size_t>(c)];
      if (j < 0) continue;  // an identity row's column: its one entry is placed
      for (int k = starts[j]; k < starts[j + 1]; ++k) {
        // entry (i, j) of K: row i, column j -> CSR row r = row_[i], column c = row_[j]
        const PetscInt r = row_[inner[k]];
        if (!keep(r)) continue;
        const PetscCount slot = next[static_cast<std::size_t>(r)]++;
        columns_[static_cast<std::size_t>(slot)] = c;
        position_[static_cast<std::size_t>(k)] = static_cast<PetscInt>(slot);
      }
    }
  }

  void createMatrix() {
    const auto [first, last] = ownedRows();
    const PetscInt local = last - first;
    check(MatCreate(PETSC_COMM_WORLD, &matrix_), "MatCreate");
    check(MatSetSizes(matrix_, local, local, size_, size_), "MatSetSizes");
    check(MatSetType(matrix_, MATAIJ), "MatSetType");
    // The block size of the embedded system (3: node blocks) is what BoomerAMG's nodal
    // coarsening and GAMG's aggregation of the rigid-body modes work on. Until the 28th session
    // MatXAIJSetPreallocation(bs = 1) reset it and one process solved without it.
    check(MatSetBlockSize(matrix_, embedded_ ? 3 : 1), "MatSetBlockSize");
    // The CSR structure exactly, assembled with zeros: the matrix's value array then has the
    // layout of columns_, and setValues writes into it through position_.
    check(MatSeqAIJSetPreallocationCSR(matrix_, rowStart_.data(), columns_.data(), nullptr),
          "MatSeqAIJSetPreallocationCSR");
    check(MatSetOption(matrix_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
    PetscInt rows = 0;
    const PetscInt *starts = nullptr, *columns = nullptr;
    PetscBool done = PETSC_FALSE;
    check(MatGetRowIJ(matrix_, 0, PETSC_FALSE, PETSC_FALSE, &rows, &starts, &columns, &done),
          "MatGetRowIJ");
    const bool same = done && rows == size_ &&
                      std::equal(rowStart_.begin(), rowStart_.end(), starts) &&
                      std::equal(columns_.begin(), columns_.end(), columns);
    check(MatRestoreRowIJ(matrix_, 0, PETSC_FALSE, PETSC_FALSE, &rows, &starts, &columns, &done),
          "MatRestoreRowIJ");
    if (!same) throw std::logic_error("PETSc: the matrix does not keep the structure it was given");
  }

  void createVectors() {
    check(MatCreateVecs(matrix_, &solution_, &rhs_), "MatCreateVecs");
    check(VecDuplicate(rhs_, &residual_), "VecDuplicate");
    if (distributed_)
      check(VecScatterCreateToAll(solution_, &toAll_, &all_), "VecScatterCreateToAll");
    if (embedded_) {
      check(VecDuplicate(solution_, &coordinates_), "VecDuplicate");
      check(VecSetBlockSize(coordinates_, 3), "VecSetBlockSize");
    }
  }

  // Several processes: each process's pattern holds its own rows complete (the other
  // processes' items add zero entries there, sparsity_pattern.hpp), so the rows it owns are
  // the local rows of the MPIAIJ matrix as they are. They are split into PETSc's diagonal and
  // off-diagonal blocks here, in arrays this object keeps and PETSc uses in place
  // (MatCreateMPIAIJWithSplitArrays), and each tangent writes its values straight into them;
  // only the nonzeros this process's items add to other processes' rows travel
  // (scatterDistributed). Until the 33rd session the structure went through PETSc's COO
  // interface, whose sort of every entry was most of an analysis (bulk 79 k deck, two
  // processes: 5.2 of 6.3 s in 32 analyses), and every tangent through MatSetValuesCOO.
  void createDistributedMatrix(const SparseMatrix& matrix) {
    numberSystem(matrix);
    buildRows(matrix, [this](PetscInt r) { return ownsRow(r); });
    splitOwnedRows();
    listRemoteEntries(matrix);
    const auto [first, last] = ownedRows();
    const PetscInt local = last - first;
    check(MatCreateMPIAIJWithSplitArrays(PETSC_COMM_WORLD, local, local, size_, size_,
                                         diagonalStart_.data(), diagonalColumns_.data(),
                                         diagonalValues_.data(), offStart_.data(),
                                         offColumns_.data(), offValues_.data(), &matrix_),
          "MatCreateMPIAIJWithSplitArrays");
    if (embedded_) check(MatSetBlockSize(matrix_, 3), "MatSetBlockSize");
    std::vector<PetscInt>().swap(columns_);
    std::vector<PetscInt>().swap(rowStart_);
  }

  // The owned rows of the CSR (buildRows) as PETSc's diagonal block (columns this process
  // owns, numbered from its first row) and off-diagonal block (global columns; PETSc renumbers
  // them in place, ascending, when it creates the matrix), and position_ and identitySlots_
  // remapped to them: a slot s >= 0 is diagonalValues_[s], s <= -2 is offValues_[-2 - s],
  // -1 a row another process owns.
  void splitOwnedRows() {
    const auto [first, last] = ownedRows();
    const std::size_t local = static_cast<std::size_t>(last - first);
    diagonalStart_.assign(local + 1, 0);
    offStart_.assign(local + 1, 0);
    const PetscCount base = rowStart_[static_cast<std::size_t>(first)];
    std::vector<PetscInt> slotOf(static_cast<std::size_t>(rowStart_[last] - base));
    diagonalColumns_.clear();
    offColumns_.clear();
    for (std::size_t i = 0; i < local; ++i) {
      const std::size_t r = static_cast<std::size_t>(first) + i;
      for (PetscCount k = rowStart_[r]; k < rowStart_[r + 1]; ++k) {
        const PetscInt c = columns_[static_cast<std::size_t>(k)];
        PetscInt& slot = slotOf[static_cast<std::size_t>(k - base)];
        if (c >= first && c < last) {
          slot = static_cast<PetscInt>(diagonalColumns_.size());
          diagonalColumns_.push_back(c - first);
        } else {
          slot = -2 - static_cast<PetscInt>(offColumns_.size());
          offColumns_.push_back(c);
        }
      }
      diagonalStart_[i + 1] = static_cast<PetscInt>(diagonalColumns_.size());
      offStart_[i + 1] = static_cast<PetscInt>(offColumns_.size());
    }
    for (PetscInt& position : position_) {
      if (position >= 0) position = slotOf[static_cast<std::size_t>(position - base)];
    }
    for (PetscCount& slot : identitySlots_) slot = slotOf[static_cast<std::size_t>(slot - base)];
    diagonalValues_.assign(diagonalColumns_.size(), 0.0);
    offValues_.assign(offColumns_.size(), 0.0);
    // PETSc reads no element of an empty block, but wants an address.
    diagonalColumns_.reserve(1);
    offColumns_.reserve(1);
    diagonalValues_.reserve(1);
    offValues_.reserve(1);
  }

  // The entries of K in rows other processes own (position_ -1), sorted by row and column, so
  // that each tangent adds them with one MatSetValues call per row and their owners insert
  // runs of a row (remoteStart_ delimits the rows' runs).
  void listRemoteEntries(const SparseMatrix& matrix) {
    struct Remote {
      PetscInt row, column;
      Eigen::Index entry;
    };
    std::vector<Remote> remote;
    for (Eigen::Index j = 0; j < equations_; ++j) {
      for (int k = matrix.outerIndexPtr()[j]; k < matrix.outerIndexPtr()[j + 1]; ++k) {
        if (position_[static_cast<std::size_t>(k)] != -1) continue;
        remote.push_back({row_[matrix.innerIndexPtr()[k]], row_[j], k});
      }
    }
    std::sort(remote.begin(), remote.end(), [](const Remote& a, const Remote& b) {
      return a.row != b.row ? a.row < b.row : a.column < b.column;
    });
    remoteRows_.clear();
    remoteStart_.assign(1, 0);
    remoteColumns_.resize(remote.size());
    remoteEntries_.resize(remote.size());
    std::size_t longest = 0;
    for (std::size_t e = 0; e < remote.size(); ++e) {
      if (e == 0 || remote[e].row != remote[e - 1].row) {
        if (e > 0) remoteStart_.push_back(e);
        remoteRows_.push_back(remote[e].row);
      }
      longest = std::max(longest, e + 1 - remoteStart_.back());
      remoteColumns_[e] = remote[e].column;
      remoteEntries_[e] = remote[e].entry;
    }
    remoteStart_.push_back(remote.size());
    remoteSendColumns_.resize(longest);
    remoteSendValues_.resize(longest);
  }

  // K's values of the rows this process owns to their places (position_): slot s >= 0 in
  // `diagonal` (one process: the matrix's value array; several: the diagonal block), s <= -2 in
  // offValues_ (several processes only); adds |diagonal| to diagonalSum.
  void scatterOwned(const SparseMatrix& matrix, PetscScalar* diagonal, double& diagonalSum) {
    const double* entries = matrix.valuePtr();
    for (Eigen::Index j = 0; j < equations_; ++j) {
      for (int k = matrix.outerIndexPtr()[j]; k < matrix.outerIndexPtr()[j + 1]; ++k) {
        if (matrix.innerIndexPtr()[k] == j) diagonalSum += std::abs(entries[k]);
        const PetscInt slot = position_[static_cast<std::size_t>(k)];
        if (slot >= 0) {
          diagonal[slot] = entries[k];
        } else if (slot <= -2) {
          offValues_[static_cast<std::size_t>(-2 - slot)] = entries[k];
        }
      }
    }
  }

  // Several processes: the owned rows into the blocks' arrays (scatterOwned), and K's nonzeros
  // in other processes' rows to PETSc's stash, row by row (listRemoteEntries), which the
  // assembly adds into their owners' rows (there, the pattern has them: sparsity_pattern.hpp).
  // Returns how many values went to other processes.
  long scatterDistributed(const SparseMatrix& matrix, double& diagonalSum) {
    scatterOwned(matrix, diagonalValues_.data(), diagonalSum);
    const double* entries = matrix.valuePtr();
    // The nonzeros only: a contact point dealt to this process that is not touching adds
    // nothing, and most of its entries lie in other processes' rows.
    long sent = 0;
    for (std::size_t r = 0; r < remoteRows_.size(); ++r) {
      PetscInt count = 0;
      for (std::size_t e = remoteStart_[r]; e < remoteStart_[r + 1]; ++e) {
        const double value = entries[remoteEntries_[e]];
        if (value == 0.0) continue;
        remoteSendValues_[static_cast<std::size_t>(count)] = value;
        remoteSendColumns_[static_cast<std::size_t>(count++)] = remoteColumns_[e];
      }
      if (count == 0) continue;
      check(MatSetValues(matrix_, 1, &remoteRows_[r], count, remoteSendColumns_.data(),
                         remoteSendValues_.data(), ADD_VALUES),
            "MatSetValues");
      sent += count;
    }
    return sent;
  }

  // The identity rows of the embedding at the scale of K's mean |diagonal|, so that they neither
  // dominate nor vanish in AMG's strength-of-connection test.
  void setIdentityRows(PetscScalar* target, double diagonalSum) const {
    const double scale = equations_ > 0 && diagonalSum > 0 ? diagonalSum / equations_ : 1.0;
    for (PetscCount slot : identitySlots_) target[slot] = scale;
  }

  void createSolver() {
    PetscBool given = PETSC_FALSE;
    check(PetscOptionsGetReal(nullptr, nullptr, "-cc_direct_residual", &directResidual_, nullptr),
          "PetscOptionsGetReal");
    check(PetscOptionsGetReal(nullptr, nullptr, "-cc_direct_backward_error", &directBackwardError_,
                              nullptr),
          "PetscOptionsGetReal");
    check(PetscOptionsGetReal(nullptr, nullptr, "-cc_hierarchy_rate_ratio", &laggedRateRatio_,
                              &given),
          "PetscOptionsGetReal");
    check(KSPCreate(PETSC_COMM_WORLD, &ksp_), "KSPCreate");
    createSolverSettings();
  }

  void createSolverSettings() {
    PC pc = nullptr;
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    switch (method_) {
      case PetscMethod::Mumps:
      case PetscMethod::SuperluDist:
        check(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
        check(PCSetType(pc, PCLU), "PCSetType");
        check(PCFactorSetMatSolverType(
                  pc, method_ == PetscMethod::Mumps ? MATSOLVERMUMPS : MATSOLVERSUPERLU_DIST),
              "PCFactorSetMatSolverType");
        if (method_ == PetscMethod::SuperluDist) {
          // SuperLU_dist pivots statically: on a sliding tangent of example 6.1 (8 k
          // equations) its solution had a relative residual of 1e-6 to 0.5 whatever the column
          // ordering (and GMRES preconditioned by it did not repair that; measured,
          // docs/performance/solvers.md). solve() checks the residual of every direct solve.
          setOption("-cc_slu_mat_superlu_dist_colperm", "METIS_AT_PLUS_A");
          check(KSPSetOptionsPrefix(ksp_, "cc_slu_"), "KSPSetOptionsPrefix");
        }
        break;
      case PetscMethod::BoomerAmg:
      case PetscMethod::Gamg:
        // Right preconditioning: GMRES then minimizes (and tests) the true residual
        // ||b - K x||, the quantity Newton's forcing term bounds.
        check(KSPSetType(ksp_, KSPGMRES), "KSPSetType");
        check(KSPGMRESSetRestart(ksp_, kGmresRestart), "KSPGMRESSetRestart");
        check(KSPSetPCSide(ksp_, PC_RIGHT), "KSPSetPCSide");
        check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
        if (method_ == PetscMethod::BoomerAmg) {
          check(PCSetType(pc, PCHYPRE), "PCSetType");
          check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
          // 3D elasticity settings (hypre's manual): strong threshold 0.5; nodal coarsening
          // on the 3 x 3 node blocks (6: Frobenius norm). Vector interpolation with the
          // rigid-body modes (vec_interp_variant 1, 2, 3) crashes in hypre 2.26's
          // hypre_BoomerAMG_LNExpandInterp / setup on our tangents (segfault, measured on
          // example 6.1): it stays off; GAMG uses the modes.
          // HMIS coarsening, ext+i interpolation truncated to 4 entries and one level of
          // aggressive coarsening (hypre's CPU recommendation for 3D): on a sliding tangent
          // of 14 k equations setup + solve took 0.61 CPU s against 0.89 s with the defaults
          // (docs/performance/solvers.md).
          setOption("-cc_amg_pc_hypre_boomeramg_strong_threshold", "0.5");
          setOption("-cc_amg_pc_hypre_boomeramg_coarsen_type", "HMIS");
          setOption("-cc_amg_pc_hypre_boomeramg_interp_type", "ext+i");
          setOption("-cc_amg_pc_hypre_boomeramg_P_max", "4");
          setOption("-cc_amg_pc_hypre_boomeramg_agg_nl", "1");
          if (embedded_) setOption("-cc_amg_pc_hypre_boomeramg_nodal_coarsen", "6");
          check(KSPSetOptionsPrefix(ksp_, "cc_amg_"), "KSPSetOptionsPrefix");
        } else {
          check(PCSetType(pc, PCGAMG), "PCSetType");
          check(KSPSetOptionsPrefix(ksp_, "cc_gamg_"), "KSPSetOptionsPrefix");
        }
        break;
    }
    // Options from the environment (PETSC_OPTIONS, e.g. -cc_amg_ksp_monitor) apply on top.
    check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
    if (iterative()) {
      auto* test = new StopTest{this, nullptr};
      check(KSPConvergedDefaultCreate(&test->defaultContext), "KSPConvergedDefaultCreate");
      check(KSPSetConvergenceTest(ksp_, convergedOrStopped, test, destroyStopTest),
            "KSPSetConvergenceTest");
    }
  }

  // PETSc's default convergence test, then the stop poll (setStopPoll): a run asked to stop
  // leaves a Krylov solve at once rather than after hundreds of iterations. Every process
  // calls this in step (the residual norm is global), so a collective poll is safe.
  struct StopTest {
    PetscSolver* solver;
    void* defaultContext;
  };
  static PetscErrorCode convergedOrStopped(KSP ksp, PetscInt iteration, PetscReal norm,
                                           KSPConvergedReason* reason, void* context) {
    auto* test = static_cast<StopTest*>(context);
    PetscCall(KSPConvergedDefault(ksp, iteration, norm, reason, test->defaultContext));
    PetscSolver& solver = *test->solver;
    if (*reason == KSP_CONVERGED_ITERATING && solver.stopPoll_ && solver.stopPoll_()) {
      solver.stopped_ = true;
      *reason = KSP_DIVERGED_NULL;
    }
    return 0;
  }
  static PetscErrorCode destroyStopTest(void* context) {
    auto* test = static_cast<StopTest*>(context);
    PetscCall(KSPConvergedDefaultDestroy(test->defaultContext));
    delete test;
    return 0;
  }

  static void setOption(const char* name, const char* value) {
    PetscBool given = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, name, &given), "PetscOptionsHasName");
    if (!given) check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
  }

  // One process: the values go straight into the matrix's value array (createMatrix gave it
  // the layout of the CSR), with no copy and no search.
  void setValues(const SparseMatrix& matrix) {
    if (distributed_) return addShares(matrix);
    double diagonalSum = 0;
    PetscScalar* values = nullptr;
    check(MatSeqAIJGetArray(matrix_, &values), "MatSeqAIJGetArray");
    scatterOwned(matrix, values, diagonalSum);
    setIdentityRows(values, diagonalSum);
    check(MatSeqAIJRestoreArray(matrix_, &values), "MatSeqAIJRestoreArray");
  }

  // Several processes: every process writes the values of its own rows in place and adds its
  // nonzeros in other processes' rows; the assembly (collective) sums those into their rows.
  void addShares(const SparseMatrix& matrix) {
    double diagonalSum = 0;
    const long remote = scatterDistributed(matrix, diagonalSum);
    // The identity rows scaled by the mean over all shares.
    double total = 0;
    MPI_Allreduce(&diagonalSum, &total, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
    setIdentityRows(diagonalValues_.data(), total);
    check(MatAssemblyBegin(matrix_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    if (const PetscErrorCode code = MatAssemblyEnd(matrix_, MAT_FINAL_ASSEMBLY); code != 0) {
      // PETSc's message above names the entry; error 63 (out of range) is a value added to
      // another process's row outside that row's pattern.
      throw std::logic_error(fmt::format(
          "PETSc: MatAssemblyEnd failed (error {}); a process's pattern must hold every item "
          "with a node it owns, also the other processes' (sparsity_pattern.hpp)",
          code));
    }
    // Each value sent carries its row and column.
    statistics_.matrixBytesSent +=
        static_cast<double>(remote) * (sizeof(PetscScalar) + 2 * sizeof(PetscInt));
  }

  // Rigid-body modes of the current configuration (three translations, three rotations).
  void setNearNullSpace() {
    if (!embedded_) return;
    PetscScalar* x = nullptr;
    check(VecGetArray(coordinates_, &x), "VecGetArray");
    const auto [first, last] = ownedRows();
    for (PetscInt r = first; r < last; ++r) {
      const PetscInt dof = dofOfRow_[static_cast<std::size_t>(r)];
      x[r - first] = layout_.coordinates(dof % 3, dof / 3);
    }
    check(VecRestoreArray(coordinates_, &x), "VecRestoreArray");
    MatNullSpace modes = nullptr;
    check(MatNullSpaceCreateRigidBody(coordinates_, &modes), "MatNullSpaceCreateRigidBody");
    check(MatSetNearNullSpace(matrix_, modes), "MatSetNearNullSpace");
    check(MatNullSpaceDestroy(&modes), "MatNullSpaceDestroy");
  }

  // Whether the last direct solve, missing kDirectResidual, is as accurate as the tangent's
  // conditioning lets any backward-stable solve be (kDirectBackwardError) and still makes a
  // Newton step (kDirectUsableResidual). Computed only after a miss, from the residual that
  // trueRelativeResidual left.
  bool solvedToRoundOff() {
    if (!(last_.relativeResidual <= kDirectUsableResidual)) return false;
    PetscReal r = 0, k = 0, x = 0, b = 0;
    check(VecNorm(residual_, NORM_INFINITY, &r), "VecNorm");
    check(MatNorm(matrix_, NORM_INFINITY, &k), "MatNorm");
    check(VecNorm(solution_, NORM_INFINITY, &x), "VecNorm");
    check(VecNorm(rhs_, NORM_INFINITY, &b), "VecNorm");
    const double scale = k * x + b;
    return scale > 0 && r <= directBackwardError_ * scale;
  }

  // ||b - K x|| / ||b|| of the last solve; b - K x stays in residual_.
  double trueRelativeResidual() {
    check(MatMult(matrix_, solution_, residual_), "MatMult");
    check(VecAYPX(residual_, -1.0, rhs_), "VecAYPX");
    PetscReal r = 0, b = 0;
    check(VecNorm(residual_, NORM_2, &r), "VecNorm");
    check(VecNorm(rhs_, NORM_2, &b), "VecNorm");
    return b > 0 ? r / b : r;
  }

  void destroy() {
    if (ksp_) KSPDestroy(&ksp_);
    if (matrix_) MatDestroy(&matrix_);
    if (solution_) VecDestroy(&solution_);
    if (rhs_) VecDestroy(&rhs_);
    if (residual_) VecDestroy(&residual_);
    if (coordinates_) VecDestroy(&coordinates_);
    if (toAll_) VecScatterDestroy(&toAll_);
    if (all_) VecDestroy(&all_);
    for (auto* indices : {&diagonalStart_, &diagonalColumns_, &offStart_, &offColumns_})
      std::vector<PetscInt>().swap(*indices);
    std::vector<PetscScalar>().swap(diagonalValues_);
    std::vector<PetscScalar>().swap(offValues_);
    factored_ = false;
    determinantSign_.reset();
    hierarchyBuilt_ = false;
  }

  PetscMethod method_;
  double relativeTolerance_ = 1e-8;
  PetscInt maxIterations_ = kKrylovIterationLimit;
  SystemLayout layout_;
  KrylovReport last_;
  std::function<bool()> stopPoll_;
  bool stopped_ = false;  // the last solve was left on the stop poll's request
  bool hierarchyBuilt_ = false, rebuildHierarchy_ = false;
  double rateAfterRebuild_ = -1;  // decades per Krylov iteration; negative: not measured yet
  PetscReal laggedRateRatio_ = kLaggedRateRatio;          // or -cc_hierarchy_rate_ratio
  PetscReal directResidual_ = kDirectResidual;            // or -cc_direct_residual
  PetscReal directBackwardError_ = kDirectBackwardError;  // or -cc_direct_backward_error
  Eigen::Index equations_ = 0, nonZeros_ = 0;
  bool embedded_ = false;
  PetscInt size_ = 0;
  std::vector<PetscInt> row_;             // equation -> PETSc row
  std::vector<PetscInt> firstRow_{0, 0};  // first row of each process, and the row count
  std::vector<PetscInt> dofOfRow_;        // embedded system: nodal dof of each row
  int rank_ = 0, processes_ = 1;
  bool distributed_ = false;
  // CSR of the rows kept (buildRows); several processes drop it once it is split in two blocks.
  std::vector<PetscInt> rowStart_, columns_;
  std::vector<PetscInt> identityRows_;  // the rows of the embedding's identity (owned ones)
  // Where each entry of K's storage goes (buildRows): into the value array (one process), into
  // the diagonal or off-diagonal block (several; splitOwnedRows says how).
  std::vector<PetscInt> position_;
  std::vector<PetscCount> identitySlots_;  // where the identity rows' entries are (as position_)
  // Several processes: the owned rows' two blocks in CSR, which the matrix uses in place (they
  // live as long as matrix_; destroy() frees them after it).
  std::vector<PetscInt> diagonalStart_, diagonalColumns_, offStart_, offColumns_;
  std::vector<PetscScalar> diagonalValues_, offValues_;
  // Several processes: K's entries in other processes' rows (listRemoteEntries) and one row's
  // nonzeros as they are sent.
  std::vector<PetscInt> remoteRows_, remoteColumns_, remoteSendColumns_;
  std::vector<std::size_t> remoteStart_;
  std::vector<Eigen::Index> remoteEntries_;
  std::vector<PetscScalar> remoteSendValues_;
  Mat matrix_ = nullptr;
  Vec solution_ = nullptr, rhs_ = nullptr, coordinates_ = nullptr;
  Vec residual_ = nullptr;      // b - K x of the last solve (trueRelativeResidual)
  VecScatter toAll_ = nullptr;  // several processes: the solution to every process
  Vec all_ = nullptr;
  KSP ksp_ = nullptr;
  bool factored_ = false;
  Mat factor_ = nullptr;                // MUMPS's factor matrix inside the PC (owned by the PC)
  PetscInt lastMumpsMargin_ = 0;        // ICNTL(14) of the last MUMPS factorization
  std::optional<int> determinantSign_;  // of the matrix MUMPS last factorized
};

}  // namespace

}  // namespace cc

// The plugin's entry points, looked up with dlsym by solver/petsc_loader.cpp.
extern "C" {
__attribute__((visibility("default"))) cc::LinearSolver* covcontact_petsc_make_solver(int method) {
  return new cc::PetscSolver(static_cast<cc::PetscMethod>(method));
}
__attribute__((visibility("default"))) void covcontact_petsc_finalize() {
  cc::petsc::finalize();
}
}
