// UMFPACK sparse LU behind the LinearSolver interface (unsymmetric tangents of frictional
// sliding, and symmetric indefinite ones that CHOLMOD rejects). UMFPACK comes in two index
// widths. The 32-bit routines (di) read Eigen's own index arrays; the 64-bit ones (dl) need
// them widened to a copy as large as the matrix's indices (150 MiB at 232 k equations), alive
// through the factorization, the run's peak. But with 32-bit indices UMFPACK runs out of
// index space (status -1, "out of memory") once its factor passes ~2^31 units (16 GiB), which
// a friction model of ~390 k equations reaches. So a solver starts with 32-bit indices and
// moves to 64-bit ones for good when an analysis estimates a factor beyond them or a 32-bit
// call runs out of memory (the 64-bit call then says whether memory really is short).
#include <fmt/format.h>
#include <umfpack.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <type_traits>
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

// UMFPACK's routines of one index width: prefix di with int, dl with SuiteSparse_long.
#define CC_UMFPACK_ROUTINES(Name, IndexType, prefix)                         \
  struct Name {                                                              \
    using Index = IndexType;                                                 \
    static constexpr auto defaults = &umfpack_##prefix##_defaults;           \
    static constexpr auto symbolic = &umfpack_##prefix##_symbolic;           \
    static constexpr auto qsymbolic = &umfpack_##prefix##_qsymbolic;         \
    static constexpr auto numeric = &umfpack_##prefix##_numeric;             \
    static constexpr auto solve = &umfpack_##prefix##_solve;                 \
    static constexpr auto getSymbolic = &umfpack_##prefix##_get_symbolic;    \
    static constexpr auto freeSymbolic = &umfpack_##prefix##_free_symbolic;  \
    static constexpr auto freeNumeric = &umfpack_##prefix##_free_numeric;    \
    static constexpr auto determinant = &umfpack_##prefix##_get_determinant; \
  }
CC_UMFPACK_ROUTINES(NarrowIndices, int, di);
CC_UMFPACK_ROUTINES(WideIndices, SuiteSparse_long, dl);
#undef CC_UMFPACK_ROUTINES

static_assert(std::is_same_v<SparseMatrix::StorageIndex, NarrowIndices::Index>,
              "the 32-bit routines read the tangent's index arrays in place");

// A 32-bit factor that would not fit its index space: the solver moves to 64-bit indices.
struct IndexSpaceExceeded {};

// Analysis, factor and solves with one index width. Work is counted in the owning solver's
// statistics.
template <class Api>
class UmfpackFactor {
 public:
  using Index = typename Api::Index;
  static constexpr bool kNarrow = std::is_same_v<Index, int>;

  // unitLimit: the largest factorization, in UMFPACK's memory units, that this width serves;
  // compactFrom: the size from which a factorization starts from a compact workspace.
  UmfpackFactor(FillOrdering ordering, double unitLimit, Eigen::Index compactFrom,
                LinearSolverStatistics& statistics)
      : unitLimit_(unitLimit), compactFrom_(compactFrom), statistics_(statistics) {
    Api::defaults(control_);
    control_[UMFPACK_ORDERING] = umfpackOrdering(ordering);
    control_[UMFPACK_IRSTEP] = 0;  // solve() refines itself, where needed (kRefineAbove)
  }
  ~UmfpackFactor() { release(); }
  UmfpackFactor(const UmfpackFactor&) = delete;
  UmfpackFactor& operator=(const UmfpackFactor&) = delete;

  void analyzePattern(const SparseMatrix& matrix) {
    const auto start = std::chrono::steady_clock::now();
    release();
    widenIndices(matrix);
    const Index size = matrix.rows();
    const bool reusedOrdering = analyzeWithKeptOrdering(matrix);
    const Index status = reusedOrdering
                             ? UMFPACK_OK
                             : Api::symbolic(size, size, columnStarts(matrix), rowIndices(matrix),
                                             matrix.valuePtr(), &symbolic_, control_, info_);
    if (kNarrow && (status == UMFPACK_ERROR_out_of_memory ||
                    (status == UMFPACK_OK && info_[UMFPACK_NUMERIC_SIZE_ESTIMATE] > unitLimit_))) {
      release();
      throw IndexSpaceExceeded{};
    }
    throwIfOutOfMemory(status, "analysis", matrix);
    if (status != UMFPACK_OK) {
      throw std::runtime_error(fmt::format("UMFPACK analysis failed (status {})", status));
    }
    // The analysis's own estimates, kept for an out-of-memory message of the factorization
    // (which overwrites info_).
    factorEstimateUnits_ = info_[UMFPACK_NUMERIC_SIZE_ESTIMATE];
    factorEstimate_ = factorEstimateUnits_ * info_[UMFPACK_SIZE_OF_UNIT];
    peakEstimate_ = info_[UMFPACK_PEAK_MEMORY_ESTIMATE] * info_[UMFPACK_SIZE_OF_UNIT];
    if (!reusedOrdering) keepOrdering(matrix);
    size_ = rows(matrix);
    ++statistics_.analyses;
    statistics_.analysisSeconds += secondsSince(start);
  }

  void factorize(const SparseMatrix& matrix) {
    if (!symbolic_ || rows(matrix) != size_) {
      throw std::logic_error("UMFPACK: factorize() before analyzePattern() of this pattern");
    }
    const auto start = std::chrono::steady_clock::now();
    if (numeric_) Api::freeNumeric(&numeric_);
    matrix_ = nullptr;
    widenIndices(matrix);  // the same pattern as analyzed; cheap next to the factorization
    control_[UMFPACK_ALLOC_INIT] =
        umfpackInitialAllocation(matrix.rows(), factorEstimateUnits_, compactFrom_);
    const Index status = Api::numeric(columnStarts(matrix), rowIndices(matrix), matrix.valuePtr(),
                                      symbolic_, &numeric_, control_, info_);
    statistics_.factorizationSeconds += secondsSince(start);
    if (kNarrow && status == UMFPACK_ERROR_out_of_memory) throw IndexSpaceExceeded{};
    ++statistics_.factorizations;
    statistics_.workspaceGrowths += static_cast<int>(std::max(0.0, info_[UMFPACK_NUMERIC_REALLOC]));
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

  // The factor applied to rhs; with `refine`, one step of iterative refinement against the
  // factorized matrix where the residual calls for it (kRefineAbove). UMFPACK's own refinement
  // (IRSTEP 2) computes componentwise backward errors and attempts a second step that it then
  // discards, on every solve measured: 10.7 ms per solve of the die model's tangent against
  // 1.75 ms for the factor alone. Without refinement (applyFactorTo alone) the matrix's values
  // are not read at all; they may belong to a later tangent by now.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs, bool refine) {
    if (!numeric_ || !matrix_) throw std::logic_error("UMFPACK: solve() without factorization");
    Eigen::VectorXd solution = applyFactorTo(rhs);
    if (!refine) return solution;
    const Eigen::VectorXd residual = rhs - *matrix_ * solution;
    if (residual.norm() > kRefineAbove * rhs.norm()) {
      solution += applyFactorTo(residual);
      ++statistics_.refinementSteps;
    }
    return solution;
  }

  void releaseFactor() {
    if (numeric_) Api::freeNumeric(&numeric_);
    matrix_ = nullptr;
  }

  // The sign of det A from the factor (the product of U's diagonal and of the permutations'
  // signs, scaling included); mantissa and exponent apart, so that no size overflows.
  std::optional<int> determinantSign() {
    if (!numeric_) return std::nullopt;
    double mantissa = 0, exponent = 0;
    if (Api::determinant(&mantissa, &exponent, numeric_, info_) != UMFPACK_OK) return std::nullopt;
    return mantissa > 0 ? 1 : mantissa < 0 ? -1 : 0;
  }

 private:
  // A solve is refined where the factor alone leaves |b - A x| above this fraction of |b|. The
  // factor alone reaches 1e-15 to 1e-14 on the tangents measured (die model: 1.8e-14 against
  // 1.2e-14 refined), where refinement gains nothing; no solve of the die deck or of example 6.1
  // needed a step. The seventh session's run without any refinement lost a contact projection
  // in a Cattaneo-Mindlin verification: most likely the projection's own round-off stall
  // (projection.cpp), but the check costs only a product with K.
  static constexpr double kRefineAbove = 1e-13;

  Eigen::VectorXd applyFactorTo(const Eigen::VectorXd& rhs) {
    Eigen::VectorXd solution(rhs.size());
    const Index status =
        Api::solve(UMFPACK_A, columnStarts(*matrix_), rowIndices(*matrix_), matrix_->valuePtr(),
                   solution.data(), rhs.data(), numeric_, control_, info_);
    if (status != UMFPACK_OK) {
      throw std::runtime_error(fmt::format("UMFPACK solve failed (status {})", status));
    }
    return solution;
  }

  static int rows(const SparseMatrix& matrix) { return static_cast<int>(matrix.rows()); }
  void release() {
    if (numeric_) Api::freeNumeric(&numeric_);
    if (symbolic_) Api::freeSymbolic(&symbolic_);
    matrix_ = nullptr;
  }

  // The 32-bit routines read Eigen's arrays in place; the 64-bit ones a widened copy.
  void widenIndices(const SparseMatrix& matrix) {
    if constexpr (!kNarrow) {
      columnStarts_.assign(matrix.outerIndexPtr(), matrix.outerIndexPtr() + matrix.cols() + 1);
      rowIndices_.assign(matrix.innerIndexPtr(), matrix.innerIndexPtr() + matrix.nonZeros());
    }
  }
  const Index* columnStarts(const SparseMatrix& matrix) const {
    if constexpr (kNarrow) return matrix.outerIndexPtr();
    return columnStarts_.data();
  }
  const Index* rowIndices(const SparseMatrix& matrix) const {
    if constexpr (kNarrow) return matrix.innerIndexPtr();
    return rowIndices_.data();
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
    const Index size = matrix.rows();
    const Index status =
        Api::qsymbolic(size, size, columnStarts(matrix), rowIndices(matrix), matrix.valuePtr(),
                       ordering_.data(), &symbolic_, givenOrderingControl_, info_);
    if (status == UMFPACK_OK) {
      ++statistics_.reusedOrderings;
      return true;
    }
    if (symbolic_) Api::freeSymbolic(&symbolic_);
    return false;
  }

  void keepOrdering(const SparseMatrix& matrix) {
    ordering_.assign(static_cast<std::size_t>(matrix.cols()), 0);
    if (Api::getSymbolic(nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr,
                         ordering_.data(), nullptr, nullptr, nullptr, nullptr, nullptr, nullptr,
                         nullptr, symbolic_) != UMFPACK_OK) {
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

  // Memory is a limit of the machine, not a step that a smaller load increment could fix.
  // The ordering (METIS, or AMD) reports only failure to UMFPACK (status -18); on a matrix
  // UMFPACK has accepted that failure is an allocation, seen under `ulimit -v` in the analysis.
  void throwIfOutOfMemory(Index status, const char* phase, const SparseMatrix& matrix) {
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

  double unitLimit_;
  Eigen::Index compactFrom_;
  LinearSolverStatistics& statistics_;
  double control_[UMFPACK_CONTROL];
  double info_[UMFPACK_INFO];
  void* symbolic_ = nullptr;
  void* numeric_ = nullptr;
  const SparseMatrix* matrix_ = nullptr;
  std::vector<Index> columnStarts_, rowIndices_;  // 64-bit only: the widened copies
  int size_ = -1;
  std::vector<Index> ordering_;                   // column preordering of the last fresh analysis
  double givenOrderingControl_[UMFPACK_CONTROL];  // control_ with that analysis's strategy
  double freshOrderingFlops_ = 0;                 // of the first factorization with it
  bool orderingStale_ = false;
  double factorEstimateUnits_ = 0;  // UMFPACK's units, from the last analysis
  double factorEstimate_ = 0;       // bytes, the same
  double peakEstimate_ = 0;
};

class UmfpackSolver final : public LinearSolver {
 public:
  UmfpackSolver(FillOrdering ordering, double narrowUnitLimit, Eigen::Index compactFrom)
      : ordering_(ordering),
        compactFrom_(compactFrom),
        narrow_(std::make_unique<UmfpackFactor<NarrowIndices>>(ordering, narrowUnitLimit,
                                                               compactFrom, statistics_)) {}

  std::string name() const override { return narrow_ ? "UMFPACK" : "UMFPACK (64-bit indices)"; }

  void analyzePattern(const SparseMatrix& matrix) override {
    checkShape(matrix);
    reserveBlasWorkspace();
    if (narrow_) {
      try {
        narrow_->analyzePattern(matrix);
        return;
      } catch (const IndexSpaceExceeded&) {
        widen();
      }
    }
    wide_->analyzePattern(matrix);
  }

  void factorize(const SparseMatrix& matrix) override {
    checkShape(matrix);
    if (narrow_) {
      try {
        narrow_->factorize(matrix);
        return;
      } catch (const IndexSpaceExceeded&) {
        widen();
        wide_->analyzePattern(matrix);
      }
    }
    wide_->factorize(matrix);
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    const auto start = std::chrono::steady_clock::now();
    Eigen::VectorXd solution = narrow_ ? narrow_->solve(rhs, true) : wide_->solve(rhs, true);
    ++statistics_.solves;
    statistics_.solveSeconds += secondsSince(start);
    return solution;
  }

  // Without refinement UMFPACK does not read the matrix values (which may belong to a later
  // tangent by now).
  Eigen::VectorXd applyFactor(const Eigen::VectorXd& rhs) override {
    return narrow_ ? narrow_->solve(rhs, false) : wide_->solve(rhs, false);
  }

  void releaseFactor() override {
    if (narrow_) narrow_->releaseFactor();
    if (wide_) wide_->releaseFactor();
  }

  std::optional<int> determinantSign() override {
    return narrow_ ? narrow_->determinantSign() : wide_->determinantSign();
  }

 private:
  static void checkShape(const SparseMatrix& matrix) {
    if (!matrix.isCompressed() || matrix.rows() != matrix.cols()) {
      throw std::invalid_argument("UMFPACK: matrix must be square and compressed");
    }
  }
  // For good: a model whose factor outgrew 32-bit indices keeps growing in a run.
  void widen() {
    narrow_.reset();
    wide_ = std::make_unique<UmfpackFactor<WideIndices>>(ordering_, 0, compactFrom_, statistics_);
  }

  FillOrdering ordering_;
  Eigen::Index compactFrom_;
  std::unique_ptr<UmfpackFactor<NarrowIndices>> narrow_;
  std::unique_ptr<UmfpackFactor<WideIndices>> wide_;
};

}  // namespace

// With 32-bit indices UMFPACK addresses its memory in Units of 8 bytes by 32-bit integers. The
// analysis's estimate of the factor is an upper bound (its estimate of the factorization's peak
// is a far looser one: 8.6 GiB and more at 232 k equations, whose factor takes 1.3 GiB); a
// factorization that needs more than the index range all the same fails with status -1 and is
// redone with 64-bit indices.
std::unique_ptr<LinearSolver> makeUmfpackSolver(FillOrdering ordering) {
  return makeUmfpackSolver(ordering, INT_MAX);
}

std::unique_ptr<LinearSolver> makeUmfpackSolver(FillOrdering ordering, double narrowUnitLimit) {
  return makeUmfpackSolver(ordering, narrowUnitLimit, kMemoryBoundSystemFrom);
}

std::unique_ptr<LinearSolver> makeUmfpackSolver(FillOrdering ordering, double narrowUnitLimit,
                                                Eigen::Index compactWorkspaceFrom) {
  umfpackOrdering(ordering);  // throws for an ordering UMFPACK does not have
  return std::make_unique<UmfpackSolver>(ordering, narrowUnitLimit, compactWorkspaceFrom);
}

double umfpackInitialAllocation(Eigen::Index equations, double factorEstimateUnits,
                                Eigen::Index compactFrom) {
  if (equations < compactFrom || !(factorEstimateUnits > 0)) return UMFPACK_DEFAULT_ALLOC_INIT;
  return -kCompactUmfpackWorkspace * factorEstimateUnits;
}

}  // namespace cc
