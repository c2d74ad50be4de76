// SIGINT and SIGTERM for the whole engine, taken by one thread with sigwait rather than by a
// signal handler. Libraries replace handlers while they run: METIS (GKlib's gk_sigtrap, entered
// by every CHOLMOD and UMFPACK fill-reducing ordering) installs its own SIGTERM handler for the
// length of an ordering, so a SIGTERM that arrived there was taken by METIS (it abandons the
// ordering) and never reached covcontact's handler: a 232 k-equation run under `timeout 30`
// went on computing until killed by hand. METIS then put the handler back with System V
// semantics (reset after one delivery). Blocked in every thread from the start of main, the two
// signals reach no handler at all, whatever a library installs; the watching thread takes them.
#pragma once

namespace cc::app {

// At the start of main, before any other thread exists (threads inherit the blocked signals;
// so does a re-executed program, which watches again). The watching thread is named
// kWatcherThreadName (/proc/PID/task/TID/comm).
inline constexpr const char* kWatcherThreadName = "cc-stop-signals";
void watchStopSignals();

// `run` from the point where a stop keeps every converged step: the first signal requests a
// stop after the current iteration, a second ends the process at once (exit code 4). Until
// then, and in the other commands, a signal ends the process as it would by default.
void stopAfterIteration();
bool stopRequested();

}  // namespace cc::app
