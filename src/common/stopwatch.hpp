// Wall-clock intervals for the work counters (solver, assembly and Newton timings): one
// definition of "seconds since", on the monotonic clock.
#pragma once

#include <chrono>

namespace cc {

inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace cc
