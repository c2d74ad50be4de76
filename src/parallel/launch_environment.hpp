// What a process launcher (mpirun, srun) tells a process through its environment, read before
// MPI is initialized. No MPI here: the `covcontact` launcher (app/launcher.cpp) reads it too.
#pragma once

namespace cc {

// Number of processes the launcher started; 1 when not launched by one.
int launchedProcesses();
// This process's rank among them (0 when not launched by one).
int launchedRank();

}  // namespace cc
