// Progress output: live terminal line or plain per-step lines.
#include "app/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

namespace cc::app {

Progress::Progress(int plannedSteps, bool quiet)
    : plannedSteps_(plannedSteps), quiet_(quiet), terminal_(isatty(fileno(stdout)) != 0) {}

void Progress::printLive(const std::string& text) {
  fmt::print("\r{:<79}", text);
  std::fflush(stdout);
  liveLineOpen_ = true;
}

void Progress::iteration(const IterationRecord& r) {
  lastRelativeResidual_ = r.relativeResidual;
  if (quiet_ || !terminal_) return;
  printLive(fmt::format("step {}/{}  t = {:.6g}  iteration {}  |R|/|R0| = {:.2e}  energy {:.2e}",
                        r.step, plannedSteps_, r.time, r.iteration, r.relativeResidual,
                        r.relativeEnergy));
}

void Progress::stepConverged(int step, double time, int iterations, int cutbacks) {
  if (quiet_) return;
  const std::string text =
      fmt::format("step {}/{}  t = {:.6g}  {} iterations{}  |R|/|R0| = {:.2e}", step, plannedSteps_,
                  time, iterations, cutbacks ? fmt::format(" after {} cut-backs", cutbacks) : "",
                  lastRelativeResidual_);
  if (terminal_) {
    printLive(text);
  } else {
    fmt::print("{}\n", text);
    std::fflush(stdout);
  }
}

void Progress::cutback(const CutbackRecord& r) {
  finish();
  fmt::print(stderr, "cut-back at step {} (t = {:.6g}): {}; new dt = {:.3g}\n", r.step, r.time,
             r.reason, r.newDt);
}

void Progress::note(const std::string& line) {
  finish();
  // The solver choice is part of the run's report; a fallback is a warning, like a cut-back.
  if (line.rfind("linear solver: ", 0) == 0) {
    if (!quiet_) fmt::print("{}\n", line);
  } else {
    fmt::print(stderr, "{}\n", line);
  }
  std::fflush(stdout);
}

void Progress::finish() {
  if (liveLineOpen_) {
    fmt::print("\n");
    liveLineOpen_ = false;
  }
}

}  // namespace cc::app
