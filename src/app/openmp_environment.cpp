// The OpenMP environment of a run (openmp_environment.hpp says which settings and why).
#include "app/openmp_environment.hpp"

#include <cstdlib>
#include <string>

#include "parallel/launch_environment.hpp"

namespace cc::app {

int runThreads(int requested) {
  // The processes share the cores.
  return requested == 0 && launchedProcesses() > 1 ? 1 : requested;
}

bool setOpenMpEnvironment(int threads) {
  bool changed = false;
  if (std::getenv("OMP_WAIT_POLICY") == nullptr) {
    changed |= setenv("OMP_WAIT_POLICY", "passive", 1) == 0;
  }
  if (threads > 0 && std::getenv("OMP_THREAD_LIMIT") == nullptr) {
    changed |= setenv("OMP_THREAD_LIMIT", std::to_string(threads).c_str(), 1) == 0;
  }
  return changed;
}

}  // namespace cc::app
