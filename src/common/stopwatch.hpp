// Wall-clock intervals for the work counters (solver, assembly and Newton timings): one
// definition of "seconds since", on the monotonic clock; and the calling thread's CPU time
// (the assembler's cost per item, which other processes' load does not inflate).
#pragma once

#include <chrono>
#include <ctime>

namespace cc {

inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline double threadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace cc
