// Prints the OpenBLAS core type the launcher sets on this CPU (app/blas_environment.hpp), for
// the test suite's environment (tests/CMakeLists.txt runs it when configuring).
#include <cstdio>

#include "app/blas_environment.hpp"

int main() {
  const char* core = cc::app::openblasCoreType(cc::app::cpuFeatures());
  std::printf("%s", core ? core : "");
  return 0;
}
