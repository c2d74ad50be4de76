// The process count and rank a launcher (mpirun, srun) puts in the environment.
#include "parallel/launch_environment.hpp"

#include <cstdlib>

namespace cc {

namespace {

int positiveFromEnvironment(const char* name) {
  const char* text = std::getenv(name);
  if (!text) return 0;
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  return end != text && *end == '\0' && value > 0 && value < (1 << 24) ? static_cast<int>(value)
                                                                       : 0;
}

}  // namespace

int launchedProcesses() {
  // Open MPI's mpirun, MPICH/Hydra or PMI-2 launchers, and Slurm's srun (which starts the
  // tasks of a job step itself; a serial run inside a batch script has no step task count).
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_STEP_NUM_TASKS"}) {
    if (const int size = positiveFromEnvironment(name)) return size;
  }
  return 1;
}

int launchedRank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "SLURM_PROCID"}) {
    if (std::getenv(name)) return positiveFromEnvironment(name);  // "0" reads as 0
  }
  return 0;
}

}  // namespace cc
