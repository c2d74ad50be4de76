// Progress output of a run: on a terminal one live line (step k of n, time, iteration,
// residual) rewritten in place; in a pipe or CI one plain line per converged step.
#pragma once

#include <cstdio>
#include <string>

#include "records/result_records.hpp"

namespace cc::app {

class Progress {
 public:
  Progress(int plannedSteps, bool quiet, bool newtonLog = false);
  void iteration(const IterationRecord& record);
  void stepConverged(int step, double time, int iterations, int cutbacks);
  void cutback(const CutbackRecord& record);
  // Ends the live line before other output.
  void finish();

 private:
  void printLive(const std::string& text);
  int plannedSteps_;
  bool quiet_;
  bool newtonLog_;
  bool terminal_;
  bool liveLineOpen_ = false;
  double lastRelativeResidual_ = 0;
};

}  // namespace cc::app
