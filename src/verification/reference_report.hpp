// Reporting reference errors: the table `covcontact run` prints after the run, and the
// /verification group it adds to the results file (layout in docs/verification/accuracy.md).
#pragma once

#include <string>
#include <vector>

#include "verification/reference_tracker.hpp"

namespace cc::verification {

// What the run cost, stored and printed beside the errors.
struct RunCost {
  double wallSeconds = 0;
  int newtonIterations = 0;
  int steps = 0;
};

// One line per reference: quantity, measured and reference value (last sample), error, largest
// relative error over the run, then the cost.
std::string formatReferenceErrors(const std::vector<ReferenceResult>& results, const RunCost& cost);

// Opens the finished results file and writes /verification (attributes wall_seconds,
// newton_iterations, steps) with one group per reference: attributes quantity, kind, analytic,
// parameters, location, time, measured, reference, error, relative_error, max_error,
// max_relative_error and datasets time, measured, reference over the sampled steps.
// Throws OutputError naming the file.
void writeReferenceErrors(const std::string& h5Path, const std::vector<ReferenceResult>& results,
                          const RunCost& cost);

}  // namespace cc::verification
