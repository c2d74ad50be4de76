// The BLAS kernels of a run. OpenBLAS, built for every x86-64 CPU ("DYNAMIC_ARCH"), picks its
// kernels from the CPU's model number when it is loaded (before main), and a model it does not
// know gets its oldest ones. Debian 12's OpenBLAS 0.3.21 does not know the AVX-512 Xeons of
// some of this workplace's machines and ran its "Prescott" (SSE3) kernels there. Kernels also
// set the round-off of every factorization, and with it, in the few round-off-sensitive cases,
// a run's Newton iterations and steps: users compare those between runs and machines.
// OpenBLAS reads OPENBLAS_CORETYPE instead of the model when it is set. The launcher and the
// program started directly set it to "Haswell" (AVX2 + FMA kernels) on every CPU that has AVX2
// and FMA, so that all such machines, Intel or AMD, with or without AVX-512, factorize with
// the same kernels. Measured on the die model's tangent (4 464 equations, UMFPACK, best of 15,
// docs/performance/solvers.md, eighteenth session): Prescott 78-80 ms, Haswell 59-61 ms,
// SkylakeX (AVX-512) 54-56 ms; the 8 % of SkylakeX are not worth machine-dependent round-off.
// The test suite runs with the same value (tests/CMakeLists.txt).
#pragma once

namespace cc::app {

struct CpuFeatures {
  bool avx2Fma = false;  // AVX2 and FMA: OpenBLAS's Haswell kernels run
};

CpuFeatures cpuFeatures();

// The OpenBLAS core type for a CPU with these features: "Haswell", or nullptr (an older CPU:
// OpenBLAS's own choice stands).
const char* openblasCoreType(const CpuFeatures& features);

// Sets OPENBLAS_CORETYPE from this CPU's features unless the user set it (or the CPU is older
// than AVX2). Returns whether it changed the environment.
bool setBlasEnvironment();

}  // namespace cc::app
