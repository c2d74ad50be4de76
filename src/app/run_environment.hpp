// The process environment of a run, shared by the engine started directly and by the benchmark
// driver (tests/regression/performance/covcontact_bench.cpp), so that a benchmark measures the
// program as `covcontact run` configures it: OpenMP settings (openmp_environment.hpp), BLAS
// kernels (blas_environment.hpp) and heap policy (heap_policy.hpp).
#pragma once

namespace cc::app {

// Puts the OpenMP settings for `threads` and the BLAS kernels into the environment and
// re-executes the program once with them (libgomp and OpenBLAS read them only when they are
// loaded, before main). Returns only if nothing changed or the exec failed (no /proc).
void applyRunEnvironment(char** argv, int threads);

}  // namespace cc::app
