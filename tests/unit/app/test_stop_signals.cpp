// The SIGINT/SIGTERM watcher (src/app/stop_signals.hpp): a handler that a library installs
// while it runs (as METIS does for every ordering) must not take covcontact's stop signal.
// Each case runs in a child process (gtest death tests), which starts watching first, as main
// does.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <thread>

#include "app/stop_signals.hpp"
#include "common/errors.hpp"

namespace {

std::atomic<int> takenByLibrary{0};
extern "C" void libraryHandler(int) {
  takenByLibrary.fetch_add(1);
}

// Waits up to 10 s for the watcher to see a stop request.
bool stopSeen() {
  for (int k = 0; k < 1000 && !cc::app::stopRequested(); ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return cc::app::stopRequested();
}

// In the child: exit code 0 when the stop arrived at the watcher and not at the library's
// handler, distinct codes for each way it can go wrong.
[[noreturn]] void signalWhileALibraryHandlerIsInstalled(int signal) {
  cc::app::watchStopSignals();
  cc::app::stopAfterIteration();
  std::signal(signal, libraryHandler);  // what GKlib's gk_sigtrap does (SIGTERM)
  ::kill(::getpid(), signal);
  const bool seen = stopSeen();
  std::_Exit(!seen ? 10 : takenByLibrary.load() != 0 ? 11 : 0);
}

}  // namespace

TEST(StopSignals, ASigtermWhileALibraryHasItsOwnHandlerInstalledStillRequestsTheStop) {
  EXPECT_EXIT(signalWhileALibraryHandlerIsInstalled(SIGTERM), testing::ExitedWithCode(0), "");
}

TEST(StopSignals, ASigintWhileALibraryHasItsOwnHandlerInstalledStillRequestsTheStop) {
  EXPECT_EXIT(signalWhileALibraryHandlerIsInstalled(SIGINT), testing::ExitedWithCode(0), "");
}

// The first signal leaves the run to stop after its iteration; a second ends it at once with
// the exit code of an interrupted run, even with a library's handler installed.
TEST(StopSignals, ASecondSignalEndsTheProcessAtOnceAsInterrupted) {
  EXPECT_EXIT(
      {
        cc::app::watchStopSignals();
        cc::app::stopAfterIteration();
        ::kill(::getpid(), SIGTERM);
        if (!stopSeen()) std::_Exit(10);
        std::signal(SIGTERM, libraryHandler);
        ::kill(::getpid(), SIGTERM);
        std::this_thread::sleep_for(std::chrono::seconds(10));
        std::_Exit(11);
      },
      testing::ExitedWithCode(cc::kExitInterrupted), "second interrupt: stopping at once");
}

// Before a run can keep its steps (and in the other commands) a signal ends the process as it
// would without covcontact's watcher: killed by that signal.
TEST(StopSignals, BeforeARunCanStopCleanlyASignalEndsTheProcessAsByDefault) {
  EXPECT_EXIT(
      {
        cc::app::watchStopSignals();
        ::kill(::getpid(), SIGTERM);
        std::this_thread::sleep_for(std::chrono::seconds(10));
        std::_Exit(11);
      },
      testing::KilledBySignal(SIGTERM), "");
}
