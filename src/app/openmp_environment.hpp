// The OpenMP settings of a run that libgomp reads only from the environment, once, when it is
// loaded (before main): set by the `covcontact` launcher before it starts the program, and by
// the program itself when started directly (it then re-executes itself once).
#pragma once

namespace cc::app {

// Threads of a run given `--threads` (0: not given): under mpirun or srun one per process unless
// --threads says more, else as given (0: all cores).
int runThreads(int requested);

// Sets, unless the user set them:
//  - OMP_WAIT_POLICY=passive: idle OpenMP threads sleep instead of spinning ~300 000 times
//    after each parallel region; on a machine whose other core is busy that spinning took a
//    third of the samples (issue 13).
//  - OMP_THREAD_LIMIT=threads when threads > 0: CHOLMOD's supernodal factorization asks for 4
//    threads whatever omp_set_num_threads says (CHOLMOD_OMP_NUM_THREADS is compiled into
//    SuiteSparse 5), so `--threads 1` ran 4 threads; the thread limit caps that too.
// Returns whether it changed the environment.
bool setOpenMpEnvironment(int threads);

}  // namespace cc::app
