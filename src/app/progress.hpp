// Progress output of a run: on a terminal one live line (step k, time of the end time, iteration,
// residual) rewritten in place; in a pipe or CI one plain line per converged step.
#pragma once

#include <cstdio>
#include <string>

#include "records/result_records.hpp"

namespace cc::app {

// Writes `text` to standard output and flushes it. If standard output is gone (`covcontact run
// DECK | head -1`, a pager quit early: EPIPE, SIGPIPE being ignored), says so once on stderr and
// drops all later output instead of ending the run: the results file is what the run is for.
void printOut(const std::string& text);
// Writes `text` to standard error; a closed stderr is ignored (nothing else could report it).
void printErr(const std::string& text);

class Progress {
 public:
  // endTime: where the last phase ends. Progress is shown as time of it, not as a step count:
  // cut-backs add steps (the plan's "step 6/5" read as a miscount).
  // liveLineAllowed: false on several processes. Open MPI gives every rank a pseudo-terminal for
  // its standard output, also when mpirun's own output goes to a file, so the ranks cannot tell
  // a terminal from a log: `mpirun ... > log` then held carriage returns and step lines run
  // together. A parallel run is a batch run; it writes plain lines.
  Progress(double endTime, bool quiet, bool newtonLog = false, bool liveLineAllowed = true);
  void iteration(const IterationRecord& record);
  // The step's final |R|/|R0| for the next stepConverged line (the load stepper reports it
  // just before every converged step).
  void convergedResidual(double relative) { convergedRelativeResidual_ = relative; }
  // stabilizationShare: the viscous stabilisation's share of the work so far (a fraction),
  // shown when positive, so that a user tuning `newton stabilize=` sees it step by step.
  void stepConverged(int step, double time, int iterations, int cutbacks,
                     double stabilizationShare = 0);
  void cutback(const CutbackRecord& record);
  // A line of its own (linear solver choice, Krylov fallback), also when quiet.
  void note(const std::string& line);
  // Ends the live line before other output.
  void finish();

 private:
  void printLive(const std::string& text);
  double endTime_;
  bool quiet_;
  bool newtonLog_;
  bool terminal_;
  bool liveLineOpen_ = false;
  double convergedRelativeResidual_ = 0;  // from convergedResidual()
};

}  // namespace cc::app
