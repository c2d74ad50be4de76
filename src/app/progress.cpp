// Progress output: live terminal line or plain per-step lines.
#include "app/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

namespace cc::app {

Progress::Progress(int plannedSteps, bool quiet, bool newtonLog)
    : plannedSteps_(plannedSteps),
      quiet_(quiet),
      newtonLog_(newtonLog),
      terminal_(isatty(fileno(stdout)) != 0) {}

void Progress::printLive(const std::string& text) {
  fmt::print("\r{:<79}", text);
  std::fflush(stdout);
  liveLineOpen_ = true;
}

void Progress::iteration(const IterationRecord& r) {
  lastRelativeResidual_ = r.relativeResidual;
  if (newtonLog_) {
    finish();
    fmt::print(
        "  step {} attempt {} iteration {}  t = {:.6g}  |R|/|R0| = {:.3e}  energy {:.3e}  "
        "contact: {} active, {} changed state, {} changed segment\n",
        r.step, r.attempt, r.iteration, r.time, r.relativeResidual, r.relativeEnergy,
        r.contact.active, r.contact.state, r.contact.segment);
    return;
  }
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

void Progress::finish() {
  if (liveLineOpen_) {
    fmt::print("\n");
    liveLineOpen_ = false;
  }
}

}  // namespace cc::app
