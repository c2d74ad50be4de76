// Progress output: live terminal line or plain per-step lines.
#include "app/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace cc::app {

void printErr(const std::string& text) {
  std::fputs(text.c_str(), stderr);  // unlike fmt::print, never throws if stderr is gone
}

void printOut(const std::string& text) {
  static bool closed = false;
  if (closed) return;
  if (std::fwrite(text.data(), 1, text.size(), stdout) == text.size() && std::fflush(stdout) == 0)
    return;
  closed = true;
  std::clearerr(stdout);
  printErr(
      fmt::format("covcontact: standard output is closed ({}); the run goes on without "
                  "progress output\n",
                  std::strerror(errno)));
}

Progress::Progress(double endTime, bool quiet, bool newtonLog, bool liveLineAllowed)
    : endTime_(endTime),
      quiet_(quiet),
      newtonLog_(newtonLog),
      terminal_(liveLineAllowed && isatty(fileno(stdout)) != 0) {}

void Progress::printLive(const std::string& text) {
  printOut(fmt::format("\r{:<79}", text));
  liveLineOpen_ = true;
}

void Progress::iteration(const IterationRecord& r) {
  if (newtonLog_) {
    finish();
    printOut(fmt::format(
        "  step {} attempt {} iteration {}  t = {:.6g}  |R|/|R0| = {:.3e}  energy {:.3e}  "
        "contact: {} active, {} changed state, {} changed segment{}{}{}\n",
        r.step, r.attempt, r.iteration, r.time, r.relativeResidual, r.relativeEnergy,
        r.contact.active, r.contact.state, r.contact.segment,
        r.determinantSign ? fmt::format("  det {}", *r.determinantSign > 0   ? "+"
                                                    : *r.determinantSign < 0 ? "-"
                                                                             : "0")
                          : std::string(),
        r.krylovTolerance > 0 ? fmt::format("  Krylov: {} iterations to {:.0e}", r.krylovIterations,
                                            r.krylovTolerance)
                              : std::string(),
        r.lineSearchFraction > 0
            ? fmt::format("  line search: {:.3g} of the update", r.lineSearchFraction)
            : std::string()));
    return;
  }
  if (quiet_ || !terminal_) return;
  printLive(
      fmt::format("step {}  t = {:.6g} of {:.6g}  iteration {}  |R|/|R0| = {:.2e}  energy {:.2e}",
                  r.step, r.time, endTime_, r.iteration, r.relativeResidual, r.relativeEnergy));
}

void Progress::stepConverged(int step, double time, int iterations, int cutbacks,
                             double stabilizationShare) {
  if (quiet_) return;
  const std::string text = fmt::format(
      "step {}  t = {:.6g} of {:.6g}  {} iterations{}  |R|/|R0| = {:.2e}{}", step, time, endTime_,
      iterations, cutbacks ? fmt::format(" after {} cut-backs", cutbacks) : "",
      convergedRelativeResidual_,
      stabilizationShare > 0
          ? fmt::format("  stabilisation {:.3g} % of the work", 100 * stabilizationShare)
          : "");
  if (terminal_) {
    printLive(text);
  } else {
    printOut(text + "\n");
  }
}

void Progress::cutback(const CutbackRecord& r) {
  finish();
  printErr(fmt::format("cut-back at step {} (t = {:.6g}): {}; new dt = {:.3g}\n", r.step, r.time,
                       r.reason, r.newDt));
}

void Progress::note(const std::string& line) {
  finish();
  // The solver choice and the predictor's choices are part of the run's report; a fallback is
  // a warning, like a cut-back.
  if (line.rfind("linear solver: ", 0) == 0 || line.rfind("predictor: ", 0) == 0) {
    if (!quiet_) printOut(line + "\n");
  } else {
    printErr(line + "\n");
  }
}

void Progress::finish() {
  if (liveLineOpen_) {
    printOut("\n");
    liveLineOpen_ = false;
  }
}

}  // namespace cc::app
