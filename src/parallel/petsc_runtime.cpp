// Once-per-process PETSc initialization, see petsc_runtime.hpp.
#include "parallel/petsc_runtime.hpp"

#include <petscsys.h>

#include <mutex>
#include <stdexcept>

namespace cc::petsc {

namespace {
std::once_flag startOnce;
bool started = false;
bool finished = false;
}  // namespace

void ensureInitialized() {
  std::call_once(startOnce, [] {
    if (finished) throw std::logic_error("PETSc: initialized again after finalize()");
    // -no_signal_handler: PETSc would otherwise replace covcontact's SIGTERM/SIGINT handlers
    // (stop after the current iteration) by its own (abort with a stack trace).
    static int argc = 2;
    static char program[] = "covcontact";
    static char noSignals[] = "-no_signal_handler";
    static char* arguments[] = {program, noSignals, nullptr};
    static char** argv = arguments;
    if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) {
      throw std::runtime_error("PETSc: PetscInitialize failed");
    }
    started = true;
  });
}

bool initialized() {
  return started && !finished;
}

void finalize() {
  if (!started || finished) return;
  PetscFinalize();
  finished = true;
}

}  // namespace cc::petsc
