// Determinant signs of a failing Newton solve's last tangents (see tangent_orientation.hpp).
#include "solver/tangent_orientation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/errors.hpp"
#include "solver/linear_solver.hpp"

namespace cc {

void TangentOrientationWatch::observe(int iteration, const SparseMatrix& tangent) {
  if (iteration < from_ || tangent.rows() == 0) return;
  Kept kept{iteration, std::nullopt, std::nullopt};
  if (!distributed_ && tangent.rows() <= kOrientationEquations) kept.tangent = tangent;
  kept_.push_back(std::move(kept));
  if (kept_.size() > static_cast<std::size_t>(kOrientationWindow)) kept_.pop_front();
}

void TangentOrientationWatch::noteSign(int iteration, std::optional<int> sign) {
  if (!kept_.empty() && kept_.back().iteration == iteration) kept_.back().sign = sign;
}

namespace {

// The sign of a kept tangent's determinant from a UMFPACK factorization of it (0: singular);
// nothing where it could not be factorized.
std::optional<int> factorizedSign(const SparseMatrix& tangent) {
  try {
    const auto solver = makeUmfpackSolver();
    solver->analyzePattern(tangent);
    solver->factorize(tangent);
    return solver->determinantSign();
  } catch (const StepFailure& failure) {
    if (failure.kind() != FailureKind::SingularSystem) return std::nullopt;
    return 0;  // singular: on the fold itself
  } catch (const std::exception&) {
    return std::nullopt;  // no factor (out of memory, OutOfMemory or bad_alloc): nothing to say
  }
}

}  // namespace

std::string TangentOrientationWatch::describe() const {
  std::vector<int> signs;
  std::vector<int> iterations;
  for (const std::deque<Kept>* window : {&earlier_, &kept_}) {
    for (const Kept& kept : *window) {
      const std::optional<int> sign = kept.sign      ? kept.sign
                                      : kept.tangent ? factorizedSign(*kept.tangent)
                                                     : std::nullopt;
      if (!sign) return {};
      signs.push_back(*sign);
      iterations.push_back(kept.iteration);
    }
  }
  const bool positive = std::find(signs.begin(), signs.end(), 1) != signs.end();
  const bool negative = std::find(signs.begin(), signs.end(), -1) != signs.end();
  if (!positive || !negative) return {};
  std::string list;
  for (std::size_t k = 0; k < signs.size(); ++k) {
    // The plain attempt's iterations first, then the retry's after a semicolon.
    const char* separator = k == 0 ? "" : k == earlier_.size() ? "; " : ", ";
    list += fmt::format("{}{} {}", separator, iterations[k],
                        signs[k] > 0   ? "+"
                        : signs[k] < 0 ? "-"
                                       : "0");
  }
  if (!earlier_.empty()) list = "the plain attempt, then its line-search retry: " + list;
  return fmt::format(
      "the tangent's determinant changes sign between these iterations ({}): with the contact "
      "states Newton passes through, equilibrium has no locally unique solution here, most "
      "likely a limit point of the frictional problem (a stick/slip instability), which smaller "
      "steps do not pass; viscous stabilisation (`newton stabilize=C`) carries a run through "
      "it at the price of a dissipation the run reports (continue from the last converged "
      "step with --restart; `stabilize_on_failure_share=F`, e.g. 0.01, stabilises only the "
      "steps that fail without it, with the factor that makes a step like the last one that "
      "passed dissipate F of its work)",
      list);
}

}  // namespace cc
