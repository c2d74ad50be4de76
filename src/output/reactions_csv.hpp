// <stem>_reactions.csv: one row per written step with the summed reaction of every named node set
// and the total force of every contact pair, for quick plots (spreadsheet, gnuplot, pandas).
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "records/result_records.hpp"

namespace cc {

class ReactionsCsv {
 public:
  // Creates (truncates) the file; the header is written with the first step, whose set and pair
  // names fix the columns of the run.
  ReactionsCsv(std::string path, bool withContact);
  ~ReactionsCsv();
  ReactionsCsv(const ReactionsCsv&) = delete;
  ReactionsCsv& operator=(const ReactionsCsv&) = delete;

  // Appends one row and flushes it to the operating system.
  void appendStep(const StepRecord& step);

 private:
  std::vector<std::string> columnNames(const StepRecord& step) const;
  void write(const std::string& text);

  std::string path_;
  bool withContact_ = true;
  std::FILE* file_ = nullptr;
  std::vector<std::string> columns_;
};

}  // namespace cc
