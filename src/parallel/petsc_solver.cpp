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
// Distribution. Rows are owned in contiguous ranges (ownedRows()); on one process that range
// is everything and the matrix is MATAIJ = SeqAIJ. The preallocation already separates the
// diagonal block from the off-process one (MatXAIJSetPreallocation with d_nnz and o_nnz), so a
// distributed assembly only has to give each rank its node range; that part is not built yet.
#include <fmt/format.h>
#include <petscksp.h>

#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "common/errors.hpp"
#include "parallel/petsc_runtime.hpp"
#include "solver/linear_solver.hpp"

namespace cc {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(fmt::format("PETSc: {} failed (error {})", what, code));
}

// Krylov iterations before a solve counts as stalled (it then falls back to a direct solve).
// BoomerAMG-GMRES needs 10-40 on the tangents measured (docs/performance/solvers.md).
constexpr PetscInt kMaxKrylovIterations = 400;
constexpr PetscInt kGmresRestart = 100;
// Relative residual above which a direct solve counts as failed (round-off of a backward-stable
// LU is ~1e-15 on our tangents; SuperLU_dist's static pivoting can miss by far more).
constexpr double kDirectResidual = 1e-8;

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
  explicit PetscSolver(PetscMethod method) : method_(method) { petsc::ensureInitialized(); }
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
  KrylovReport lastSolve() const override { return last_; }

  void analyzePattern(const SparseMatrix& matrix) override {
    if (!matrix.isCompressed() || matrix.rows() != matrix.cols()) {
      throw std::invalid_argument("PETSc: matrix must be square and compressed");
    }
    const auto start = std::chrono::steady_clock::now();
    destroy();
    buildStructure(matrix);
    createMatrix();
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
    setValues(matrix);
    if (iterative()) setNearNullSpace();
    check(KSPSetOperators(ksp_, matrix_, matrix_), "KSPSetOperators");
    PC pc = nullptr;
    check(KSPGetPC(ksp_, &pc), "KSPGetPC");
    Mat factor = nullptr;
    if (method_ == PetscMethod::Mumps) {
      // Null-pivot detection (ICNTL 24) with the threshold of the other direct solvers
      // (CNTL 3 relative to ||A||): without it MUMPS factors a singular tangent silently.
      check(PCFactorSetUpMatSolverType(pc), "PCFactorSetUpMatSolverType");
      check(PCFactorGetMatrix(pc, &factor), "PCFactorGetMatrix");
      check(MatMumpsSetIcntl(factor, 24, 1), "MatMumpsSetIcntl");
      check(MatMumpsSetCntl(factor, 3, kSingularPivotRatio), "MatMumpsSetCntl");
    }
    // Direct: the numeric factorization; iterative: the AMG hierarchy of this matrix.
    const PetscErrorCode code = KSPSetUp(ksp_);
    PCFailedReason reason = PC_NOERROR;
    check(PCGetFailedReason(pc, &reason), "PCGetFailedReason");
    PetscInt nullPivots = 0;
    if (factor && code == 0) check(MatMumpsGetInfog(factor, 28, &nullPivots), "MatMumpsGetInfog");
    if (nullPivots > 0) reason = PC_FACTOR_NUMERIC_ZEROPIVOT;
    statistics_.factorizationSeconds += secondsSince(start);
    if (code != 0 || reason != PC_NOERROR) {
      ++statistics_.failedFactorizations;
      throw StepFailure(FailureKind::SingularSystem,
                        fmt::format("{}: factorization failed ({}; a body free to move as a "
                                    "rigid body, or a missing support?)",
                                    name(), code != 0 ? "error" : PCFailedReasons[reason]));
    }
    factored_ = true;
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    if (!factored_) throw std::logic_error("PETSc: solve() without factorization");
    const auto start = std::chrono::steady_clock::now();
    PetscScalar* values = nullptr;
    check(VecSet(rhs_, 0.0), "VecSet");
    check(VecGetArray(rhs_, &values), "VecGetArray");
    for (Eigen::Index e = 0; e < equations_; ++e) values[row_[e]] = rhs[e];
    check(VecRestoreArray(rhs_, &values), "VecRestoreArray");
    if (iterative()) {
      check(KSPSetTolerances(ksp_, relativeTolerance_, 0.0, 1e5, maxIterations_),
            "KSPSetTolerances");
    }
    check(KSPSolve(ksp_, rhs_, solution_), "KSPSolve");
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
    // A direct solve whose residual is far above round-off did not solve the system.
    if (!iterative() && !(last_.relativeResidual <= kDirectResidual))
      reason = KSP_DIVERGED_BREAKDOWN;
    if (reason < 0) {
      throw KrylovFailure(fmt::format(
          "{}: {} after {} iterations (relative residual {:.3g}, "
          "asked {:.3g})",
          name(), last_.reason, iterations, last_.relativeResidual, relativeTolerance_));
    }
    Eigen::VectorXd result(equations_);
    const PetscScalar* x = nullptr;
    check(VecGetArrayRead(solution_, &x), "VecGetArrayRead");
    for (Eigen::Index e = 0; e < equations_; ++e) result[e] = x[row_[e]];
    check(VecRestoreArrayRead(solution_, &x), "VecRestoreArrayRead");
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
  }

 private:
  // The rows this process owns: all of them until the distributed issue splits them by nodes.
  std::pair<PetscInt, PetscInt> ownedRows() const { return {0, size_}; }

  // CSR of the (embedded) system in PETSc's row numbering, and where each entry of Eigen's
  // column-major storage lands in it (K is not symmetric in general: CSR of K = CSC of K^T).
  void buildStructure(const SparseMatrix& matrix) {
    equations_ = matrix.rows();
    nonZeros_ = matrix.nonZeros();
    const bool embed = iterative() &&
                       static_cast<Eigen::Index>(layout_.freeDofs.size()) == equations_ &&
                       layout_.coordinates.cols() > 0;
    embedded_ = embed;
    size_ = embed ? static_cast<PetscInt>(3 * layout_.coordinates.cols())
                  : static_cast<PetscInt>(equations_);
    row_.resize(static_cast<std::size_t>(equations_));
    for (Eigen::Index e = 0; e < equations_; ++e) {
      row_[e] = embed ? layout_.freeDofs[static_cast<std::size_t>(e)] : static_cast<PetscInt>(e);
      if (e > 0 && row_[e] <= row_[e - 1]) {
        throw std::invalid_argument("PETSc: SystemLayout::freeDofs must ascend");
      }
    }
    std::vector<bool> isFree(static_cast<std::size_t>(size_), !embed);
    for (PetscInt r : row_) isFree[static_cast<std::size_t>(r)] = true;
    // Row lengths: entries of column j of K go to row row_[j] (transposed storage).
    std::vector<PetscInt> length(static_cast<std::size_t>(size_), 0);
    for (Eigen::Index j = 0; j < equations_; ++j) {
      for (int k = matrix.outerIndexPtr()[j]; k < matrix.outerIndexPtr()[j + 1]; ++k) {
        ++length[static_cast<std::size_t>(row_[matrix.innerIndexPtr()[k]])];
      }
    }
    for (PetscInt r = 0; r < size_; ++r) {
      if (!isFree[static_cast<std::size_t>(r)]) length[static_cast<std::size_t>(r)] = 1;
    }
    rowStart_.assign(static_cast<std::size_t>(size_) + 1, 0);
    for (PetscInt r = 0; r < size_; ++r) rowStart_[r + 1] = rowStart_[r] + length[r];
    columns_.assign(static_cast<std::size_t>(rowStart_.back()), 0);
    values_.assign(columns_.size(), 0.0);
    position_.assign(static_cast<std::size_t>(nonZeros_), 0);
    std::vector<PetscInt> next(rowStart_.begin(), rowStart_.end() - 1);
    // Columns visited in ascending order, so every CSR row comes out sorted.
    for (Eigen::Index j = 0; j < equations_; ++j) {
      for (int k = matrix.outerIndexPtr()[j]; k < matrix.outerIndexPtr()[j + 1]; ++k) {
        const PetscInt r = row_[matrix.innerIndexPtr()[k]];
        // entry (i, j) of K: row i, column j -> stored in CSR row r = row_[i], column row_[j]
        position_[static_cast<std::size_t>(k)] = next[r];
        columns_[static_cast<std::size_t>(next[r]++)] = row_[j];
      }
    }
    identityRows_.clear();
    for (PetscInt r = 0; r < size_; ++r) {
      if (isFree[static_cast<std::size_t>(r)]) continue;
      columns_[static_cast<std::size_t>(rowStart_[r])] = r;
      identityRows_.push_back(r);
    }
  }

  void createMatrix() {
    const auto [first, last] = ownedRows();
    const PetscInt local = last - first;
    check(MatCreate(PETSC_COMM_WORLD, &matrix_), "MatCreate");
    check(MatSetSizes(matrix_, local, local, size_, size_), "MatSetSizes");
    check(MatSetType(matrix_, MATAIJ), "MatSetType");
    if (embedded_) check(MatSetBlockSize(matrix_, 3), "MatSetBlockSize");
    std::vector<PetscInt> diagonal(static_cast<std::size_t>(local)), offDiagonal(diagonal.size());
    for (PetscInt r = first; r < last; ++r) {
      for (PetscInt k = rowStart_[r]; k < rowStart_[r + 1]; ++k) {
        const PetscInt c = columns_[static_cast<std::size_t>(k)];
        ++(c >= first && c < last ? diagonal : offDiagonal)[static_cast<std::size_t>(r - first)];
      }
    }
    check(
        MatXAIJSetPreallocation(matrix_, 1, diagonal.data(), offDiagonal.data(), nullptr, nullptr),
        "MatXAIJSetPreallocation");
    check(MatSetOption(matrix_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE), "MatSetOption");
    check(MatCreateVecs(matrix_, &solution_, &rhs_), "MatCreateVecs");
    if (embedded_) {
      check(VecDuplicate(solution_, &coordinates_), "VecDuplicate");
      check(VecSetBlockSize(coordinates_, 3), "VecSetBlockSize");
    }
  }

  void createSolver() {
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
  }

  static void setOption(const char* name, const char* value) {
    PetscBool given = PETSC_FALSE;
    check(PetscOptionsHasName(nullptr, nullptr, name, &given), "PetscOptionsHasName");
    if (!given) check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
  }

  void setValues(const SparseMatrix& matrix) {
    const double* entries = matrix.valuePtr();
    double diagonalSum = 0;
    for (Eigen::Index j = 0; j < equations_; ++j) {
      for (int k = matrix.outerIndexPtr()[j]; k < matrix.outerIndexPtr()[j + 1]; ++k) {
        values_[static_cast<std::size_t>(position_[static_cast<std::size_t>(k)])] = entries[k];
        if (matrix.innerIndexPtr()[k] == j) diagonalSum += std::abs(entries[k]);
      }
    }
    // Identity rows of the embedding at the scale of K's diagonal, so that they neither
    // dominate nor vanish in AMG's strength-of-connection test.
    const double scale = equations_ > 0 && diagonalSum > 0 ? diagonalSum / equations_ : 1.0;
    for (PetscInt r : identityRows_) values_[static_cast<std::size_t>(rowStart_[r])] = scale;
    const auto [first, last] = ownedRows();
    for (PetscInt r = first; r < last; ++r) {
      const PetscInt count = rowStart_[r + 1] - rowStart_[r];
      check(MatSetValues(matrix_, 1, &r, count, columns_.data() + rowStart_[r],
                         values_.data() + rowStart_[r], INSERT_VALUES),
            "MatSetValues");
    }
    check(MatAssemblyBegin(matrix_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check(MatAssemblyEnd(matrix_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  }

  // Rigid-body modes of the current configuration (three translations, three rotations).
  void setNearNullSpace() {
    if (!embedded_) return;
    PetscScalar* x = nullptr;
    check(VecGetArray(coordinates_, &x), "VecGetArray");
    const auto [first, last] = ownedRows();
    for (PetscInt r = first; r < last; ++r) x[r - first] = layout_.coordinates(r % 3, r / 3);
    check(VecRestoreArray(coordinates_, &x), "VecRestoreArray");
    MatNullSpace modes = nullptr;
    check(MatNullSpaceCreateRigidBody(coordinates_, &modes), "MatNullSpaceCreateRigidBody");
    check(MatSetNearNullSpace(matrix_, modes), "MatSetNearNullSpace");
    check(MatNullSpaceDestroy(&modes), "MatNullSpaceDestroy");
  }

  double trueRelativeResidual() {
    Vec residual = nullptr;
    check(VecDuplicate(rhs_, &residual), "VecDuplicate");
    check(MatMult(matrix_, solution_, residual), "MatMult");
    check(VecAYPX(residual, -1.0, rhs_), "VecAYPX");
    PetscReal r = 0, b = 0;
    check(VecNorm(residual, NORM_2, &r), "VecNorm");
    check(VecNorm(rhs_, NORM_2, &b), "VecNorm");
    check(VecDestroy(&residual), "VecDestroy");
    return b > 0 ? r / b : r;
  }

  void destroy() {
    if (ksp_) KSPDestroy(&ksp_);
    if (matrix_) MatDestroy(&matrix_);
    if (solution_) VecDestroy(&solution_);
    if (rhs_) VecDestroy(&rhs_);
    if (coordinates_) VecDestroy(&coordinates_);
    factored_ = false;
  }

  PetscMethod method_;
  double relativeTolerance_ = 1e-8;
  PetscInt maxIterations_ = kMaxKrylovIterations;
  SystemLayout layout_;
  KrylovReport last_;
  Eigen::Index equations_ = 0, nonZeros_ = 0;
  bool embedded_ = false;
  PetscInt size_ = 0;
  std::vector<PetscInt> row_;  // equation -> PETSc row
  std::vector<PetscInt> rowStart_, columns_, position_, identityRows_;
  std::vector<PetscScalar> values_;
  Mat matrix_ = nullptr;
  Vec solution_ = nullptr, rhs_ = nullptr, coordinates_ = nullptr;
  KSP ksp_ = nullptr;
  bool factored_ = false;
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
