// Comparison of two runs' results files (numdiff style), behind `covcontact compare RUN REFERENCE`:
// step counts, times and Newton iteration counts must agree, chosen fields within tolerance.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace cc {

struct CompareOptions {
  // Values a, b agree when |a - b| <= max(atol, rtol * max(|a|, |b|)).
  double rtol = 1e-8;
  // Absolute floor; unset = kDefaultAtolFactor times the largest |value| the reference file holds
  // for that field over all steps, so roundoff around zero entries does not count.
  std::optional<double> atol;
  // Dataset paths relative to a step group; "*" stands for every child group (every contact pair).
  // A pattern without "*" that matches no dataset in either file is reported as a mismatch.
  std::vector<std::string> fields = {"set_reactions", "contact/*/total_force"};
  int maxReported = 20;  // mismatches listed in the report (all are counted)
};

// 1e-10: sums of many contact or reaction forces that cancel (an x reaction of a symmetric press
// step) carry round-off of ~1e-11 of the field's largest value, which changes with the
// fill-reducing ordering, the BLAS or the optimization level; differences below that are not
// results.
inline constexpr double kDefaultAtolFactor = 1e-10;

struct Mismatch {
  int step = 0;       // 0 when the mismatch is not about one step (e.g. the step count)
  std::string field;  // "iterations", "time", "step count", or a dataset path
  std::string index;  // "top.z", "[12, y]", or a note such as "missing in run"
  double runValue = 0;
  double referenceValue = 0;
  double relativeDifference = 0;
};

struct CompareResult {
  bool match = true;
  long mismatchCount = 0;
  std::vector<Mismatch> reported;  // the first CompareOptions::maxReported mismatches
  std::string report;              // readable text: settings, the listed mismatches, a verdict
};

// Both arguments are results files written by ResultsWriter. Throws OutputError if one cannot be
// read; every difference in content is a mismatch in the result instead.
CompareResult compareRuns(const std::string& run, const std::string& reference,
                          const CompareOptions& options = {});

}  // namespace cc
