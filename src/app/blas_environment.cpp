// The BLAS kernels of a run (blas_environment.hpp says why).
#include "app/blas_environment.hpp"

#include <cstdlib>

namespace cc::app {

CpuFeatures cpuFeatures() {
  __builtin_cpu_init();
  CpuFeatures features;
  features.avx2Fma = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return features;
}

const char* openblasCoreType(const CpuFeatures& features) {
  return features.avx2Fma ? "Haswell" : nullptr;
}

bool setBlasEnvironment() {
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr) return false;
  const char* core = openblasCoreType(cpuFeatures());
  return core != nullptr && setenv("OPENBLAS_CORETYPE", core, 1) == 0;
}

}  // namespace cc::app
