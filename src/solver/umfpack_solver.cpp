// UMFPACK sparse LU behind the LinearSolver interface (unsymmetric tangents of frictional
// sliding, and symmetric indefinite ones that CHOLMOD rejects). The 64-bit-index (dl) routines:
// with 32-bit indices UMFPACK runs out of index space (status -1, "out of memory") once the LU
// factor passes ~2^31 entries, which a friction model of ~390 k equations already reaches.
#include <fmt/format.h>
#include <umfpack.h>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <stdexcept>
#include <vector>

#include "common/errors.hpp"
#include "common/stopwatch.hpp"
#include "solver/linear_solver.hpp"

namespace cc {

namespace {

int umfpackOrdering(FillOrdering ordering) {
  switch (ordering) {
    case FillOrdering::Amd:
      return UMFPACK_ORDERING_AMD;
    case FillOrdering::Metis:
      return UMFPACK_ORDERING_METIS;
    case FillOrdering::Automatic:
      return UMFPACK_ORDERING_CHOLMOD;
    case FillOrdering::NestedDissection:
      break;
  }
  throw std::invalid_argument("UMFPACK has no nested-dissection ordering of its own");
}

class UmfpackSolver final : public LinearSolver {
 public:
  explicit UmfpackSolver(FillOrdering ordering) {
    umfpack_dl_defaults(control_);
    control_[UMFPACK_ORDERING] = umfpackOrdering(ordering);
    std::copy(std::begin(control_), std::end(control_), std::begin(unrefinedControl_));
    unrefinedControl_[UMFPACK_IRSTEP] = 0;
  }
  ~UmfpackSolver() override { release(); }
  UmfpackSolver(const UmfpackSolver&) = delete;
  UmfpackSolver& operator=(const UmfpackSolver&) = delete;

  std::string name() const override { return "UMFPACK"; }

  void analyzePattern(const SparseMatrix& matrix) override {
    checkShape(matrix);
    reserveBlasWorkspace();
    const auto start = std::chrono::steady_clock::now();
    release();
    copyIndices(matrix);
    const SuiteSparse_long size = matrix.rows();
    const bool reusedOrdering = analyzeWithKeptOrdering(matrix);
    const SuiteSparse_long status =
        reusedOrdering ? UMFPACK_OK
                       : umfpack_dl_symbolic(size, size, columnStarts_.data(), rowIndices_.data(),
                                             matrix.valuePtr(), &symbolic_, control_, info_);
    throwIfOutOfMemory(status, "analysis", matrix);
    if (status != UMFPACK_OK) {
      throw std::runtime_error(fmt::format("UMFPACK analysis failed (status {})", status));
    }
    // The analysis's own estimates, kept for an out-of-memory message of the factorization
    // (which overwrites info_).
    factorEstimate_ = info_[UMFPACK_NUMERIC_SIZE_ESTIMATE] * info_[UMFPACK_SIZE_OF_UNIT];
    peakEstimate_ = info_[UMFPACK_PEAK_MEMORY_ESTIMATE] * info_[UMFPACK_SIZE_OF_UNIT];
    if (!reusedOrdering) keepOrdering(matrix);
    size_ = rows(matrix);
    ++statistics_.analyses;
    statistics_.analysisSeconds += secondsSince(start);
  }

  void factorize(const SparseMatrix& matrix) override {
    checkShape(matrix);
    if (!symbolic_ || rows(matrix) != size_) {
      throw std::logic_error("UMFPACK: factorize() before analyzePattern() of this pattern");
    }
    const auto start = std::chrono::steady_clock::now();
    ++statistics_.factorizations;
    if (numeric_) umfpack_dl_free_numeric(&numeric_);
    matrix_ = nullptr;
    copyIndices(matrix);  // the same pattern as analyzed; cheap next to the factorization
    const SuiteSparse_long status =
        umfpack_dl_numeric(columnStarts_.data(), rowIndices_.data(), matrix.valuePtr(), symbolic_,
                           &numeric_, control_, info_);
    statistics_.factorizationSeconds += secondsSince(start);
    throwIfOutOfMemory(status, "factorization", matrix);
    if (status == UMFPACK_WARNING_singular_matrix) {
      ++statistics_.failedFactorizations;
      throw StepFailure(FailureKind::SingularSystem,
                        "UMFPACK: tangent singular (zero pivot; a body free to move as a rigid "
                        "body, or a missing support?)");
    }
    if (status != UMFPACK_OK) {
      ++statistics_.failedFactorizations;
      throw std::runtime_error(fmt::format("UMFPACK factorization failed (status {})", status));
    }
    statistics_.largestFactorFlops = std::max(statistics_.largestFactorFlops, info_[UMFPACK_FLOPS]);
    judgeOrdering(info_[UMFPACK_FLOPS]);
    // UMFPACK_NUMERIC_SIZE: the final size of the Numeric object (L, U, indices), in Units.
    statistics_.largestFactorBytes = std::max(
        statistics_.largestFactorBytes, info_[UMFPACK_NUMERIC_SIZE] * info_[UMFPACK_SIZE_OF_UNIT]);
    // UMFPACK_RCOND is min |U_ii| / max |U_ii| of the scaled factor.
    const double pivotRatio = info_[UMFPACK_RCOND];
    if (!(pivotRatio >= kSingularPivotRatio)) {
      ++statistics_.failedFactorizations;
      throw StepFailure(FailureKind::SingularSystem,
                        fmt::format("UMFPACK: tangent numerically singular (smallest/largest "
                                    "pivot {:.3g})",
                                    pivotRatio));
    }
    matrix_ = &matrix;
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    const auto start = std::chrono::steady_clock::now();
    Eigen::VectorXd solution = solveWith(rhs, control_);
    ++statistics_.solves;
    statistics_.solveSeconds += secondsSince(start);
    return solution;
  }

  // Without refinement UMFPACK does not read the matrix values (which may belong to a later
  // tangent by now).
  Eigen::VectorXd applyFactor(const Eigen::VectorXd& rhs) override {
    return solveWith(rhs, unrefinedControl_);
  }

  void releaseFactor() override {
    if (numeric_) umfpack_dl_free_numeric(&numeric_);
    matrix_ = nullptr;
  }

 private:
  Eigen::VectorXd solveWith(const Eigen::VectorXd& rhs, const double* control) {
    if (!numeric_ || !matrix_) throw std::logic_error("UMFPACK: solve() without factorization");
    Eigen::VectorXd solution(rhs.size());
    const SuiteSparse_long status =
        umfpack_dl_solve(UMFPACK_A, columnStarts_.data(), rowIndices_.data(), matrix_->valuePtr(),
                         solution.data(), rhs.data(), numeric_, control, info_);
    if (status != UMFPACK_OK) {
      throw std::runtime_error(fmt::format("UMFPACK solve failed (status {})", status));
    }
    return solution;
  }

  static int rows(const SparseMatrix& matrix) { return static_cast<int>(matrix.rows()); }
  static void checkShape(const SparseMatrix& matrix) {
    if (!matrix.isCompressed() || matrix.rows() != matrix.cols()) {
      throw std::invalid_argument("UMFPACK: matrix must be square and compressed");
    }
  }
  void release() {
    if (numeric_) umfpack_dl_free_numeric(&numeric_);
    if (symbolic_) umfpack_dl_free_symbolic(&symbolic_);
    matrix_ = nullptr;
  }
  // Ordering reuse. The fill-reducing ordering (METIS on A + A^T) is most of an analysis, and a
  // contact run analyzes a new pattern whenever a contact point changes its master segment: on
  // the die-dragging model 73 analyses in 40 steps, at 23 ms each against 68 ms per
  // factorization. A new pattern differs from the last by a few contact couplings, so the
  // ordering of the last fresh analysis still serves: it is given to UMFPACK (qsymbolic, with
  // the strategy that analysis chose) until a factorization needs more than kStaleOrderingFlops
  // times the flops of the first factorization with it; the next pattern is ordered afresh.
  // (The analysis's own flop estimate is an upper bound that hardly moves: on the die model
  // it grew by 6 % while the factorizations' flops grew by 60 %.)
  static constexpr double kStaleOrderingFlops = 1.2;

  bool analyzeWithKeptOrdering(const SparseMatrix& matrix) {
    if (orderingStale_ || ordering_.empty() ||
        static_cast<Eigen::Index>(ordering_.size()) != matrix.cols()) {
      return false;
    }
    const SuiteSparse_long size = matrix.rows();
    const SuiteSparse_long status = umfpack_dl_qsymbolic(
        size, size, columnStarts_.data(), rowIndices_.data(), matrix.valuePtr(), ordering_.data(),
        &symbolic_, givenOrderingControl_, info_);
    if (status == UMFPACK_OK) {
      ++statistics_.reusedOrderings;
      return true;
    }
    if (symbolic_) umfpack_dl_free_symbolic(&symbolic_);
    return false;
  }

  void keepOrdering(const SparseMatrix& matrix) {
    ordering_.assign(static_cast<std::size_t>(matrix.cols()), 0);
    if (umfpack_dl_get_symbolic(nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr,
                                ordering_.data(), nullptr, nullptr, nullptr, nullptr, nullptr,
                                nullptr, nullptr, symbolic_) != UMFPACK_OK) {
      ordering_.clear();
      return;
    }
    std::copy(std::begin(control_), std::end(control_), std::begin(givenOrderingControl_));
    givenOrderingControl_[UMFPACK_STRATEGY] =
        info_[UMFPACK_STRATEGY_USED] == UMFPACK_STRATEGY_SYMMETRIC ? UMFPACK_STRATEGY_SYMMETRIC
                                                                   : UMFPACK_STRATEGY_UNSYMMETRIC;
    freshOrderingFlops_ = 0;
    orderingStale_ = false;
  }

  void judgeOrdering(double flops) {
    if (freshOrderingFlops_ == 0) {
      freshOrderingFlops_ = flops;
    } else if (flops > kStaleOrderingFlops * freshOrderingFlops_) {
      orderingStale_ = true;
    }
  }

  // Eigen's 32-bit column starts and row indices widened for the dl routines.
  void copyIndices(const SparseMatrix& matrix) {
    columnStarts_.assign(matrix.outerIndexPtr(), matrix.outerIndexPtr() + matrix.cols() + 1);
    rowIndices_.assign(matrix.innerIndexPtr(), matrix.innerIndexPtr() + matrix.nonZeros());
  }
  // Memory is a limit of the machine, not a step that a smaller load increment could fix.
  // The ordering (METIS, or AMD) reports only failure to UMFPACK (status -18); on a matrix
  // UMFPACK has accepted that failure is an allocation, seen under `ulimit -v` in the analysis.
  void throwIfOutOfMemory(SuiteSparse_long status, const char* phase, const SparseMatrix& matrix) {
    if (status == UMFPACK_ERROR_ordering_failed) {
      throw OutOfMemory(fmt::format(
          "UMFPACK's fill-reducing ordering failed in the {} of the {} x {} tangent ({} "
          "nonzeros; status {}), which on a valid tangent means that it ran out of memory: "
          "the LU factor of this model does not fit; use fewer elements or a machine with "
          "more memory",
          phase, matrix.rows(), matrix.cols(), matrix.nonZeros(), status));
    }
    if (status != UMFPACK_ERROR_out_of_memory) return;
    constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
    const std::string estimate =
        symbolic_ && factorEstimate_ > 0
            ? fmt::format(
                  "; the analysis estimated the LU factor at {:.2f} GiB and the peak "
                  "memory of the factorization at {:.2f} GiB (an upper bound)",
                  factorEstimate_ / kGiB, peakEstimate_ / kGiB)
            : std::string();
    throw OutOfMemory(fmt::format(
        "UMFPACK ran out of memory in the {} of the {} x {} tangent ({} nonzeros){}: the LU "
        "factor of this model does not fit; use fewer elements or a machine with more memory",
        phase, matrix.rows(), matrix.cols(), matrix.nonZeros(), estimate));
  }

  double control_[UMFPACK_CONTROL];
  double unrefinedControl_[UMFPACK_CONTROL];  // control_ with UMFPACK_IRSTEP 0
  double info_[UMFPACK_INFO];
  void* symbolic_ = nullptr;
  void* numeric_ = nullptr;
  const SparseMatrix* matrix_ = nullptr;
  std::vector<SuiteSparse_long> columnStarts_, rowIndices_;
  int size_ = -1;
  std::vector<SuiteSparse_long> ordering_;        // column preordering of the last fresh analysis
  double givenOrderingControl_[UMFPACK_CONTROL];  // control_ with that analysis's strategy
  double freshOrderingFlops_ = 0;                 // of the first factorization with it
  bool orderingStale_ = false;
  double factorEstimate_ = 0;  // bytes, from the last analysis
  double peakEstimate_ = 0;
};

}  // namespace

std::unique_ptr<LinearSolver> makeUmfpackSolver(FillOrdering ordering) {
  return std::make_unique<UmfpackSolver>(ordering);
}

}  // namespace cc
