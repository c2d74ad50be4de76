// Reference-aware runs (issue 6): the deck's `reference` lines, checked when the model is built,
// sampled on every converged step, and summarized as errors (final and largest) at the end.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "records/result_records.hpp"

namespace cc::verification {

struct ReferenceSample {
  double time = 0;
  double measured = 0;
  double reference = 0;
};

struct ReferenceResult {
  std::string quantity;    // as written in the deck
  std::string kind;        // "value", "table" or "analytic"
  std::string analytic;    // solution name (kind "analytic")
  std::string parameters;  // "R=10 E=1000 ..." (kind "analytic")
  std::string location;    // deck file:line
  // One sample per converged step where the reference applies: every step for a value, the
  // steps inside the table's time range, the loaded steps for an analytic solution.
  std::vector<ReferenceSample> samples;
  // Of the last sample: measured - reference, and that relative to the reference scale (|value|,
  // max |table value|, |analytic value|); NaN when the scale is zero.
  double error = 0;
  double relativeError = 0;
  // Largest |error| and |relative error| over all samples.
  double maxError = 0;
  double maxRelativeError = 0;
};

class ReferenceTracker {
 public:
  // Checks every reference line of the model's deck (quantity, analytic name and parameters,
  // probe nodes); throws InputError at the offending line.
  explicit ReferenceTracker(const Model& model);
  ~ReferenceTracker();
  ReferenceTracker(const ReferenceTracker&) = delete;
  ReferenceTracker& operator=(const ReferenceTracker&) = delete;

  bool empty() const;
  // Records the measured and reference values of a converged step.
  void observe(const StepRecord& step);
  std::vector<ReferenceResult> results() const;

 private:
  struct Entry;
  std::vector<std::unique_ptr<Entry>> entries_;
};

}  // namespace cc::verification
