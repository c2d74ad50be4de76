// The process environment of a run (run_environment.hpp says what it owns).
#include "app/run_environment.hpp"

#include <unistd.h>

#include "app/blas_environment.hpp"
#include "app/openmp_environment.hpp"

namespace cc::app {

void applyRunEnvironment(char** argv, int threads) {
  const bool openMp = setOpenMpEnvironment(threads);
  const bool blas = setBlasEnvironment();
  if (openMp || blas) execv("/proc/self/exe", argv);
  // exec failed (no /proc): go on with the defaults
}

}  // namespace cc::app
