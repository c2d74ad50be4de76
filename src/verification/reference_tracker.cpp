// ReferenceTracker: one entry per `reference` line, each a measured/reference pair of functions
// of a converged step, and the error summary over the sampled steps.
#include "verification/reference_tracker.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>

#include "verification/analytic_reference.hpp"
#include "verification/quantity.hpp"

namespace cc::verification {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Piecewise-linear interpolation inside the table's range; nullopt outside it.
std::optional<double> interpolate(const std::vector<std::pair<double, double>>& table, double t) {
  if (table.empty() || t < table.front().first || t > table.back().first) return std::nullopt;
  auto upper = std::lower_bound(table.begin(), table.end(), t,
                                [](const auto& point, double time) { return point.first < time; });
  if (upper == table.begin()) return upper->second;
  const auto lower = upper - 1;
  const double weight = (t - lower->first) / (upper->first - lower->first);
  return lower->second + weight * (upper->second - lower->second);
}

std::string parameterText(const ReferenceSpec& spec) {
  std::string text;
  for (const auto& [name, value] : spec.parameters) {
    text += fmt::format("{}{}={:g}", text.empty() ? "" : " ", name, value);
  }
  return text;
}

}  // namespace

struct ReferenceTracker::Entry {
  ReferenceResult result;
  std::function<double(const StepRecord&)> measured;
  std::function<std::optional<double>(const StepRecord&)> reference;
  // The scale that turns an error into a relative error; zero for per-sample analytic values.
  double fixedScale = 0;
  bool perSampleScale = false;
};

ReferenceTracker::ReferenceTracker(const Model& model) {
  for (const ReferenceSpec& spec : model.spec().references) {
    auto entry = std::make_unique<Entry>();
    const Quantity quantity = parseQuantity(spec.quantity, model, spec.where);
    entry->result.quantity = spec.quantity;
    entry->result.location = spec.where.str();
    entry->measured = [quantity, &mesh = model.mesh()](const StepRecord& step) {
      return measure(quantity, step, mesh);
    };
    if (spec.value) {
      entry->result.kind = "value";
      const double value = *spec.value;
      entry->reference = [value](const StepRecord&) { return std::optional<double>(value); };
      entry->fixedScale = std::abs(value);
    } else if (!spec.table.empty()) {
      entry->result.kind = "table";
      const auto table = spec.table;
      entry->reference = [table](const StepRecord& step) { return interpolate(table, step.time); };
      for (const auto& point : table)
        entry->fixedScale = std::max(entry->fixedScale, std::abs(point.second));
    } else {
      entry->result.kind = "analytic";
      entry->result.analytic = spec.analytic;
      entry->result.parameters = parameterText(spec);
      AnalyticComparison comparison = makeAnalyticComparison(spec, quantity, model);
      entry->measured = std::move(comparison.measured);
      entry->reference = std::move(comparison.reference);
      entry->perSampleScale = true;
    }
    entries_.push_back(std::move(entry));
  }
}

ReferenceTracker::~ReferenceTracker() = default;

bool ReferenceTracker::empty() const {
  return entries_.empty();
}

void ReferenceTracker::observe(const StepRecord& step) {
  for (auto& entry : entries_) {
    const std::optional<double> reference = entry->reference(step);
    if (!reference) continue;
    entry->result.samples.push_back({step.time, entry->measured(step), *reference});
  }
}

std::vector<ReferenceResult> ReferenceTracker::results() const {
  std::vector<ReferenceResult> results;
  for (const auto& entry : entries_) {
    ReferenceResult result = entry->result;
    result.error = result.relativeError = kNaN;
    for (const ReferenceSample& sample : result.samples) {
      const double error = sample.measured - sample.reference;
      const double scale = entry->perSampleScale ? std::abs(sample.reference) : entry->fixedScale;
      const double relative = scale > 0 ? error / scale : kNaN;
      result.error = error;
      result.relativeError = relative;
      result.maxError = std::max(result.maxError, std::abs(error));
      if (!std::isnan(relative)) {
        result.maxRelativeError = std::max(result.maxRelativeError, std::abs(relative));
      }
    }
    if (result.samples.empty() || std::isnan(result.relativeError)) result.maxRelativeError = kNaN;
    results.push_back(std::move(result));
  }
  return results;
}

}  // namespace cc::verification
