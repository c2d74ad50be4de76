// CHOLMOD supernodal Cholesky (A = L L^T) behind the LinearSolver interface, called through
// CHOLMOD's C API so that the ordering, the failing pivot and the condition estimate are ours.
#include <cholmod.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/errors.hpp"
#include "common/stopwatch.hpp"
#include "solver/linear_solver.hpp"

namespace cc {

namespace {

// A non-owning CHOLMOD view of an Eigen matrix; stype = 1: only the upper triangle is read.
cholmod_sparse viewOf(const SparseMatrix& matrix) {
  if (!matrix.isCompressed() || matrix.rows() != matrix.cols()) {
    throw std::invalid_argument("CHOLMOD: matrix must be square and compressed");
  }
  cholmod_sparse view{};
  view.nrow = static_cast<std::size_t>(matrix.rows());
  view.ncol = static_cast<std::size_t>(matrix.cols());
  view.nzmax = static_cast<std::size_t>(matrix.nonZeros());
  view.p = const_cast<int*>(matrix.outerIndexPtr());
  view.i = const_cast<int*>(matrix.innerIndexPtr());
  view.x = const_cast<double*>(matrix.valuePtr());
  view.stype = 1;
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  return view;
}

int cholmodOrdering(FillOrdering ordering) {
  switch (ordering) {
    case FillOrdering::Amd:
      return CHOLMOD_AMD;
    case FillOrdering::Metis:
      return CHOLMOD_METIS;
    case FillOrdering::NestedDissection:
      return CHOLMOD_NESDIS;
    case FillOrdering::Automatic:
      break;
  }
  return CHOLMOD_AMD;
}

// OpenBLAS on x86-64 (Debian's libopenblas0-serial 0.3.21) maps a work buffer of BUFFER_SIZE =
// 128 MiB plus a page at its first level-3 or LAPACK call and keeps it for the process; when
// that mapping fails its blas_memory_alloc tries again forever. Probing with a little more
// address space than that tells whether the buffer would fit; another BLAS build with a larger
// buffer would escape the probe (then the hang under a tight limit is back).
constexpr std::size_t kBlasWorkspaceProbe = (std::size_t{129} << 20);

}  // namespace

void reserveBlasWorkspace() {
  static std::mutex mutex;
  static bool reserved = false;
  const std::lock_guard<std::mutex> lock(mutex);
  if (reserved) return;
  void* probe = std::malloc(kBlasWorkspaceProbe);
  if (!probe) {
    throw OutOfMemory(fmt::format(
        "the BLAS library's work buffer ({} MiB of address space, taken at the first "
        "factorization) does not fit in the memory left after building the model; use fewer "
        "elements or a machine with more memory",
        kBlasWorkspaceProbe >> 20));
  }
  std::free(probe);
  // A 1 x 1 supernodal Cholesky factorization: CHOLMOD calls LAPACK's dpotrf on its supernode,
  // which takes the buffer while the probe says it fits.
  cholmod_common common{};
  cholmod_start(&common);
  common.print = 0;
  common.supernodal = CHOLMOD_SUPERNODAL;
  SparseMatrix unit(1, 1);
  unit.insert(0, 0) = 1.0;
  unit.makeCompressed();
  cholmod_sparse one = viewOf(unit);
  cholmod_factor* factor = cholmod_analyze(&one, &common);
  if (factor) cholmod_factorize(&one, factor, &common);
  const int status = common.status;
  if (factor) cholmod_free_factor(&factor, &common);
  cholmod_finish(&common);
  if (status == CHOLMOD_OUT_OF_MEMORY) {
    throw OutOfMemory(
        "CHOLMOD ran out of memory factoring a 1 x 1 matrix before the first "
        "factorization: almost no memory is left after building the model; use "
        "fewer elements or a machine with more memory");
  }
  reserved = true;
}

namespace {

class CholmodSolver final : public LinearSolver {
 public:
  explicit CholmodSolver(FillOrdering ordering) {
    cholmod_start(&common_);
    common_.print = 0;  // failures are reported as exceptions, not printed
    common_.supernodal = CHOLMOD_SUPERNODAL;
    if (ordering != FillOrdering::Automatic) {
      common_.nmethods = 1;
      common_.method[0].ordering = cholmodOrdering(ordering);
    }
  }
  ~CholmodSolver() override {
    if (factor_) cholmod_free_factor(&factor_, &common_);
    if (symbolic_) cholmod_free_factor(&symbolic_, &common_);
    cholmod_finish(&common_);
  }
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  std::string name() const override { return "CHOLMOD"; }

  // CHOLMOD_OUT_OF_MEMORY (-2) and CHOLMOD_TOO_LARGE (-3, the factor's size overflows its
  // integers): a limit of the machine or the library, said with the sizes involved.
  void throwIfOutOfMemory(const char* phase, const SparseMatrix& matrix) const {
    if (common_.status != CHOLMOD_OUT_OF_MEMORY && common_.status != CHOLMOD_TOO_LARGE) return;
    // A supernodal factor stores xsize values (the supernodes' dense blocks, fill included) and
    // ssize row indices, both known after the analysis; otherwise lnz values and indices.
    const double bytes = symbolic_ && symbolic_->is_super
                             ? 8.0 * static_cast<double>(symbolic_->xsize) +
                                   4.0 * static_cast<double>(symbolic_->ssize)
                             : 12.0 * common_.lnz;
    const std::string estimate =
        symbolic_ && common_.lnz > 0
            ? fmt::format("; the analysis estimated {:.3g} nonzeros in the factor, {:.2f} GiB",
                          common_.lnz, bytes / (1u << 30))
            : std::string();
    throw OutOfMemory(fmt::format(
        "CHOLMOD {} in the {} of the {} x {} tangent ({} nonzeros){}: the Cholesky factor of "
        "this model does not fit; use fewer elements or a machine with more memory",
        common_.status == CHOLMOD_TOO_LARGE ? "found the problem too large for its integers"
                                            : "ran out of memory",
        phase, matrix.rows(), matrix.cols(), matrix.nonZeros(), estimate));
  }

  void analyzePattern(const SparseMatrix& matrix) override {
    reserveBlasWorkspace();
    const auto start = std::chrono::steady_clock::now();
    factorized_ = false;
    if (factor_) cholmod_free_factor(&factor_, &common_);
    if (symbolic_) cholmod_free_factor(&symbolic_, &common_);
    cholmod_sparse view = viewOf(matrix);
    if (!analyzeWithKeptOrdering(view)) {
      symbolic_ = cholmod_analyze(&view, &common_);
      if (symbolic_) keepOrdering();
    }
    if (!symbolic_) {
      throwIfOutOfMemory("analysis", matrix);
      throw std::runtime_error(fmt::format("CHOLMOD analysis failed (status {})", common_.status));
    }
    ++statistics_.analyses;
    statistics_.largestFactorFlops = std::max(statistics_.largestFactorFlops, common_.fl);
    statistics_.analysisSeconds += secondsSince(start);
  }

  void factorize(const SparseMatrix& matrix) override {
    factorized_ = false;
    if (!symbolic_ || symbolic_->n != static_cast<std::size_t>(matrix.rows())) {
      throw std::logic_error("CHOLMOD: factorize() before analyzePattern() of this pattern");
    }
    const auto start = std::chrono::steady_clock::now();
    if (!factor_) factor_ = cholmod_copy_factor(symbolic_, &common_);
    if (!factor_) {
      throwIfOutOfMemory("factor allocation", matrix);
      throw std::runtime_error(
          fmt::format("CHOLMOD: out of memory for the factor (status {})", common_.status));
    }
    ++statistics_.factorizations;
    cholmod_sparse view = viewOf(matrix);
    cholmod_factorize(&view, factor_, &common_);
    statistics_.factorizationSeconds += secondsSince(start);
    if (common_.status == CHOLMOD_NOT_POSDEF || factor_->minor < factor_->n) {
      ++statistics_.failedFactorizations;
      const std::size_t pivot = factor_->minor;
      const int equation = static_cast<const int*>(factor_->Perm)[pivot];
      throw StepFailure(FailureKind::SingularSystem,
                        fmt::format("CHOLMOD: tangent not positive definite (pivot {} of {} "
                                    "fails, free equation {})",
                                    pivot + 1, factor_->n, equation));
    }
    if (common_.status < CHOLMOD_OK) {
      ++statistics_.failedFactorizations;
      throwIfOutOfMemory("factorization", matrix);
      throw std::runtime_error(
          fmt::format("CHOLMOD factorization failed (status {})", common_.status));
    }
    statistics_.largestFactorBytes = std::max(statistics_.largestFactorBytes, factorBytes());
    // cholmod_rcond is (min L_ii / max L_ii)^2, the pivot ratio of A = L D L^T.
    const double pivotRatio = cholmod_rcond(factor_, &common_);
    if (!(pivotRatio >= kSingularPivotRatio)) {
      ++statistics_.failedFactorizations;
      throw StepFailure(FailureKind::SingularSystem,
                        fmt::format("CHOLMOD: tangent numerically singular (smallest/largest "
                                    "pivot {:.3g})",
                                    pivotRatio));
    }
    factorized_ = true;
  }

  // A Cholesky factor exists only for a positive definite matrix (a failed one throws).
  std::optional<int> determinantSign() override {
    return factorized_ ? std::optional<int>(1) : std::nullopt;
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    const auto start = std::chrono::steady_clock::now();
    Eigen::VectorXd result = applyFactor(rhs);
    ++statistics_.solves;
    statistics_.solveSeconds += secondsSince(start);
    return result;
  }

  // CHOLMOD does not refine: a solve is the factor applied.
  Eigen::VectorXd applyFactor(const Eigen::VectorXd& rhs) override {
    if (!factor_) throw std::logic_error("CHOLMOD: solve() without factorization");
    cholmod_dense right{};
    right.nrow = static_cast<std::size_t>(rhs.size());
    right.ncol = 1;
    right.nzmax = right.nrow;
    right.d = right.nrow;
    right.x = const_cast<double*>(rhs.data());
    right.xtype = CHOLMOD_REAL;
    right.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* solution = cholmod_solve(CHOLMOD_A, factor_, &right, &common_);
    if (!solution) {
      throw std::runtime_error(fmt::format("CHOLMOD solve failed (status {})", common_.status));
    }
    Eigen::VectorXd result =
        Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(solution->x), rhs.size());
    cholmod_free_dense(&solution, &common_);
    return result;
  }

  // The numeric factor goes; the analysis (symbolic_) stays for the next factorize().
  void releaseFactor() override {
    factorized_ = false;
    if (factor_) cholmod_free_factor(&factor_, &common_);
  }

 private:
  // Ordering reuse (as in umfpack_solver.cpp): a contact run analyzes a new pattern whenever a
  // contact point changes its master segment, and the fill-reducing ordering (nested
  // dissection) is most of an analysis. The permutation of the last fresh analysis is given to
  // CHOLMOD for a new pattern of the same size unless the flops it then counts exceed
  // kStaleOrderingFlops times those of the fresh analysis; the pattern is then ordered afresh.
  static constexpr double kStaleOrderingFlops = 1.2;

  bool analyzeWithKeptOrdering(cholmod_sparse& view) {
    if (ordering_.empty() || ordering_.size() != view.nrow) return false;
    const int methods = common_.nmethods;
    const auto method = common_.method[0];
    common_.nmethods = 1;
    common_.method[0].ordering = CHOLMOD_GIVEN;
    symbolic_ = cholmod_analyze_p(&view, ordering_.data(), nullptr, 0, &common_);
    common_.nmethods = methods;
    common_.method[0] = method;
    if (symbolic_ && common_.fl <= kStaleOrderingFlops * freshOrderingFlops_) {
      ++statistics_.reusedOrderings;
      return true;
    }
    if (symbolic_) cholmod_free_factor(&symbolic_, &common_);
    ordering_.clear();
    return false;
  }

  void keepOrdering() {
    const int* permutation = static_cast<const int*>(symbolic_->Perm);
    ordering_.assign(permutation, permutation + symbolic_->n);
    freshOrderingFlops_ = common_.fl;
  }

  // Values plus integer indices of the factor (supernodal: x and s; simplicial: x and i).
  double factorBytes() const {
    const double indices = factor_->is_super ? static_cast<double>(factor_->ssize)
                                             : static_cast<double>(factor_->nzmax);
    const double values = factor_->is_super ? static_cast<double>(factor_->xsize)
                                            : static_cast<double>(factor_->nzmax);
    return values * sizeof(double) + indices * sizeof(int);
  }

  cholmod_common common_{};
  cholmod_factor* symbolic_ = nullptr;  // the analysis of the current pattern
  std::vector<int> ordering_;           // permutation of the last fresh analysis
  double freshOrderingFlops_ = 0;       // counted by that analysis
  cholmod_factor* factor_ = nullptr;    // numeric factor, a copy of symbolic_ factorized
  bool factorized_ = false;             // factor_ holds the last factorize()'s matrix
};

}  // namespace

std::unique_ptr<LinearSolver> makeCholmodSolver(FillOrdering ordering) {
  return std::make_unique<CholmodSolver>(ordering);
}

}  // namespace cc
