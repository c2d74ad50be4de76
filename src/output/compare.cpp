// compareRuns: step-by-step comparison of two results files with numdiff-style tolerances and a
// readable list of the first mismatches.
#include "output/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "output/results_layout.hpp"
#include "output/results_reader.hpp"

namespace cc {

namespace {

constexpr const char* kAxisNames[3] = {"x", "y", "z"};
constexpr int kVectorComponents = 3;

std::string formatValue(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.16e", value);
  return text;
}

std::vector<std::string> split(const std::string& path) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t slash; (slash = path.find('/', start)) != std::string::npos; start = slash + 1)
    parts.push_back(path.substr(start, slash - start));
  parts.push_back(path.substr(start));
  return parts;
}

// Concrete dataset paths (relative to the step group) matching a pattern with "*" components.
void expandPattern(const ResultsReader& file, const std::string& stepGroup,
                   const std::vector<std::string>& parts, size_t depth, const std::string& prefix,
                   std::set<std::string>& found) {
  const std::string joined = prefix.empty() ? "" : prefix + "/";
  const std::string group = prefix.empty() ? stepGroup : stepGroup + "/" + prefix;
  if (depth + 1 == parts.size()) {
    if (parts[depth] == "*") {
      for (const std::string& child : file.children(group))
        if (file.hasDataset(stepGroup + "/" + joined + child)) found.insert(joined + child);
    } else if (file.hasDataset(stepGroup + "/" + joined + parts[depth])) {
      found.insert(joined + parts[depth]);
    }
    return;
  }
  if (parts[depth] != "*") {
    expandPattern(file, stepGroup, parts, depth + 1, joined + parts[depth], found);
    return;
  }
  for (const std::string& child : file.children(group))
    expandPattern(file, stepGroup, parts, depth + 1, joined + child, found);
}

bool agree(double a, double b, double rtol, double atol) {
  if (a == b) return true;                          // also equal infinities
  if (std::isnan(a) && std::isnan(b)) return true;  // e.g. the gap of a point that is not projected
  return std::abs(a - b) <= std::max(atol, rtol * std::max(std::abs(a), std::abs(b)));
}

double relativeDifference(double a, double b) {
  const double scale = std::max(std::abs(a), std::abs(b));
  return scale > 0 ? std::abs(a - b) / scale : 0.0;
}

// Largest finite |value| of a field over the given steps of one file.
double largestMagnitude(const ResultsReader& file, const std::vector<StepHeader>& steps,
                        const std::string& field) {
  double largest = 0;
  for (const StepHeader& step : steps) {
    const std::string path = step.group + "/" + field;
    if (!file.hasDataset(path)) continue;
    const Eigen::MatrixXd values = file.readMatrix(path);
    for (const double value : values.reshaped())
      if (std::isfinite(value)) largest = std::max(largest, std::abs(value));
  }
  return largest;
}

class Comparison {
 public:
  Comparison(const ResultsReader& run, const ResultsReader& reference,
             const CompareOptions& options)
      : run_(run), reference_(reference), options_(options) {}

  void compareSteps();
  void compareField(const std::string& pattern);
  CompareResult finish() const;

 private:
  void record(Mismatch mismatch);
  void compareValues(const StepHeader& step, const std::string& field, double atol);
  std::string indexLabel(const std::string& field, const std::vector<std::string>& setNames,
                         Eigen::Index row, Eigen::Index col, Eigen::Index cols) const;

  const ResultsReader& run_;
  const ResultsReader& reference_;
  const CompareOptions& options_;
  std::vector<StepHeader> commonSteps_;  // reference headers of steps present in both files
  CompareResult result_;
};

void Comparison::record(Mismatch mismatch) {
  result_.match = false;
  ++result_.mismatchCount;
  if (static_cast<int>(result_.reported.size()) < options_.maxReported)
    result_.reported.push_back(std::move(mismatch));
}

void Comparison::compareSteps() {
  std::map<int, StepHeader> runSteps;
  for (StepHeader& header : run_.steps()) runSteps.emplace(header.step, std::move(header));
  const std::vector<StepHeader> referenceSteps = reference_.steps();
  if (runSteps.size() != referenceSteps.size())
    record({0, "step count", "", static_cast<double>(runSteps.size()),
            static_cast<double>(referenceSteps.size()), 0});
  double maxTime = 0;
  for (const StepHeader& step : referenceSteps) maxTime = std::max(maxTime, std::abs(step.time));
  const double timeFloor = kDefaultAtolFactor * maxTime;
  for (const StepHeader& expected : referenceSteps) {
    const auto found = runSteps.find(expected.step);
    if (found == runSteps.end()) {
      record({expected.step, "step", "missing in run", 0, 0, 0});
      continue;
    }
    const StepHeader& actual = found->second;
    commonSteps_.push_back(expected);
    if (!agree(actual.time, expected.time, options_.rtol, timeFloor))
      record({expected.step, "time", "", actual.time, expected.time,
              relativeDifference(actual.time, expected.time)});
    if (actual.iterations != expected.iterations)
      record({expected.step, "iterations", "", static_cast<double>(actual.iterations),
              static_cast<double>(expected.iterations), 0});
    if (actual.cutbacks != expected.cutbacks)
      record({expected.step, "cutbacks", "", static_cast<double>(actual.cutbacks),
              static_cast<double>(expected.cutbacks), 0});
  }
}

void Comparison::compareField(const std::string& pattern) {
  const std::vector<std::string> parts = split(pattern);
  std::set<std::string> fields;
  for (const StepHeader& step : commonSteps_) {
    expandPattern(run_, step.group, parts, 0, "", fields);
    expandPattern(reference_, step.group, parts, 0, "", fields);
  }
  if (fields.empty() && pattern.find('*') == std::string::npos && !commonSteps_.empty())
    record({0, pattern, "not found in either file", 0, 0, 0});
  for (const std::string& field : fields) {
    const double atol =
        options_.atol ? *options_.atol
                      : kDefaultAtolFactor * largestMagnitude(reference_, commonSteps_, field);
    for (const StepHeader& step : commonSteps_) compareValues(step, field, atol);
  }
}

void Comparison::compareValues(const StepHeader& step, const std::string& field, double atol) {
  const std::string path = step.group + "/" + field;
  const bool inRun = run_.hasDataset(path);
  const bool inReference = reference_.hasDataset(path);
  if (inRun != inReference) {
    record({step.step, field, inRun ? "missing in reference" : "missing in run", 0, 0, 0});
    return;
  }
  if (!inRun) return;
  const Eigen::MatrixXd actual = run_.readMatrix(path);
  const Eigen::MatrixXd expected = reference_.readMatrix(path);
  if (actual.rows() != expected.rows() || actual.cols() != expected.cols()) {
    record({step.step, field,
            "shape " + std::to_string(actual.rows()) + "x" + std::to_string(actual.cols()) +
                " vs " + std::to_string(expected.rows()) + "x" + std::to_string(expected.cols()),
            0, 0, 0});
    return;
  }
  std::vector<std::string> setNames;
  if (field == layout::kSetReactions) {
    setNames = reference_.stringListAttribute(path, "names");
    if (run_.stringListAttribute(path, "names") != setNames) {
      record({step.step, field, "node set names differ", 0, 0, 0});
      return;
    }
  }
  for (Eigen::Index row = 0; row < expected.rows(); ++row)
    for (Eigen::Index col = 0; col < expected.cols(); ++col) {
      const double a = actual(row, col);
      const double b = expected(row, col);
      if (!agree(a, b, options_.rtol, atol))
        record({step.step, field, indexLabel(field, setNames, row, col, expected.cols()), a, b,
                relativeDifference(a, b)});
    }
}

std::string Comparison::indexLabel(const std::string& field,
                                   const std::vector<std::string>& setNames, Eigen::Index row,
                                   Eigen::Index col, Eigen::Index cols) const {
  const bool vectorRows = cols == kVectorComponents;
  if (!setNames.empty() && vectorRows)
    return setNames[static_cast<size_t>(row)] + "." + kAxisNames[col];
  if (field.ends_with(layout::kTotalForce) && cols == 1 && row < kVectorComponents)
    return kAxisNames[row];
  if (vectorRows) return "[" + std::to_string(row) + ", " + kAxisNames[col] + "]";
  if (cols == 1) return "[" + std::to_string(row) + "]";
  return "[" + std::to_string(row) + ", " + std::to_string(col) + "]";
}

CompareResult Comparison::finish() const {
  CompareResult result = result_;
  std::string text = "compare '" + run_.path() + "' against reference '" + reference_.path() +
                     "'\n  rtol " + formatValue(options_.rtol) + ", atol " +
                     (options_.atol ? formatValue(*options_.atol)
                                    : formatValue(kDefaultAtolFactor) + " x field max") +
                     "; fields:";
  for (const std::string& field : options_.fields) text += " " + field;
  text += "\n";
  if (result.match) {
    text += "MATCH: " + std::to_string(commonSteps_.size()) + " steps agree\n";
    result.report = text;
    return result;
  }
  char line[256];
  std::snprintf(line, sizeof line, "%6s  %-32s %-16s %24s %24s %10s\n", "step", "field", "index",
                "run", "reference", "rel.diff");
  text += line;
  for (const Mismatch& mismatch : result.reported) {
    const bool valued = mismatch.runValue != 0 || mismatch.referenceValue != 0;
    std::snprintf(line, sizeof line, "%6d  %-32s %-16s %24s %24s %10.3e\n", mismatch.step,
                  mismatch.field.c_str(), mismatch.index.c_str(),
                  valued ? formatValue(mismatch.runValue).c_str() : "-",
                  valued ? formatValue(mismatch.referenceValue).c_str() : "-",
                  mismatch.relativeDifference);
    text += line;
  }
  text += "MISMATCH: " + std::to_string(result.mismatchCount) + " difference(s)";
  if (result.mismatchCount > static_cast<long>(result.reported.size()))
    text += ", first " + std::to_string(result.reported.size()) + " shown";
  result.report = text + "\n";
  return result;
}

}  // namespace

CompareResult compareRuns(const std::string& run, const std::string& reference,
                          const CompareOptions& options) {
  const ResultsReader runFile(run);
  const ResultsReader referenceFile(reference);
  Comparison comparison(runFile, referenceFile, options);
  comparison.compareSteps();
  for (const std::string& field : options.fields) comparison.compareField(field);
  return comparison.finish();
}

}  // namespace cc
