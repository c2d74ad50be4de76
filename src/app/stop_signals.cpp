// The SIGINT/SIGTERM watcher (stop_signals.hpp says why it is not a handler).
#include "app/stop_signals.hpp"

#include <pthread.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <thread>

#include "common/errors.hpp"

namespace cc::app {

namespace {

std::atomic<bool> stopMode{false};
std::atomic<bool> stopSignal{false};

sigset_t stopSignals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  return signals;
}

// The default action of `signal` (end the process, reported as killed by it), from this thread.
[[noreturn]] void endAsByDefault(int signal) {
  std::signal(signal, SIG_DFL);
  sigset_t only;
  sigemptyset(&only);
  sigaddset(&only, signal);
  pthread_sigmask(SIG_UNBLOCK, &only, nullptr);
  raise(signal);
  ::_exit(128 + signal);  // not reached
}

[[noreturn]] void watch(sigset_t signals) {
  for (;;) {
    int signal = 0;
    if (sigwait(&signals, &signal) != 0) continue;
    if (!stopMode.load()) endAsByDefault(signal);
    if (!stopSignal.exchange(true)) continue;
    static const char kMessage[] =
        "\ncovcontact: second interrupt: stopping at once; the steps written so far are kept\n";
    [[maybe_unused]] const auto written = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    ::_exit(kExitInterrupted);
  }
}

}  // namespace

void watchStopSignals() {
  const sigset_t signals = stopSignals();
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread watcher(watch, signals);
  // Named, so that a count of a run's computing threads can leave it out (it sleeps in sigwait:
  // `--threads 1` still computes on one thread; robustness.launcher_environment).
  pthread_setname_np(watcher.native_handle(), kWatcherThreadName);
  watcher.detach();
}

void stopAfterIteration() {
  stopSignal.store(false);
  stopMode.store(true);
}

bool stopRequested() {
  return stopSignal.load();
}

}  // namespace cc::app
