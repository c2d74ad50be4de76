// dlopen of the PETSc plugin, see petsc_loader.hpp. The plugin is found at the path the build
// compiled in (COVCONTACT_PETSC_MODULE), unless the environment variable of the same name names
// another one.
#include "solver/petsc_loader.hpp"

#include <dlfcn.h>
#include <fmt/format.h>
#include <sys/resource.h>

#include <cstdlib>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <string>

#include "common/errors.hpp"
#include "solver/linear_solver.hpp"

namespace cc {

namespace {

using MakeSolver = LinearSolver* (*)(int);
using Finalize = void (*)();

struct Plugin {
  void* handle = nullptr;
  MakeSolver make = nullptr;
  Finalize finalize = nullptr;
};

std::once_flag loadOnce;
Plugin plugin;
std::string loadError;

void load() {
  const char* fromEnvironment = std::getenv("COVCONTACT_PETSC_MODULE");
  const std::string path = fromEnvironment ? fromEnvironment : COVCONTACT_PETSC_MODULE;
  // RTLD_LOCAL: PETSc's libraries stay out of the global symbol scope of the process.
  plugin.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!plugin.handle) {
    loadError = dlerror();
    return;
  }
  plugin.make = reinterpret_cast<MakeSolver>(dlsym(plugin.handle, "covcontact_petsc_make_solver"));
  plugin.finalize = reinterpret_cast<Finalize>(dlsym(plugin.handle, "covcontact_petsc_finalize"));
  if (!plugin.make || !plugin.finalize) loadError = path + ": entry points missing";
}

// `what` names what needs the plugin, `instead` what to do without it.
void loadOrThrow(const char* what, const char* instead) {
  std::call_once(loadOnce, load);
  if (!loadError.empty()) {
    throw std::runtime_error(std::string(what) + " not available (" + loadError + "); " + instead +
                             "install PETSc with scripts/install-deps.sh and rebuild");
  }
}

// Loading the plugin maps PETSc's ~50 libraries and starting MPI creates threads: VmPeak of
// example 6.1 (2 k equations, one thread) is 378 MiB with UMFPACK, 520 with GAMG and 627 with
// MUMPS. Under an address-space limit (ulimit -v) that leaves less, Open MPI's start-up does not
// return an error: it aborts the process (pmix_init cannot start its progress thread).
constexpr long kPetscStartupBytes = 320L << 20;

// Address space the limit leaves now; -1 without a limit.
long addressSpaceLeft() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return -1;
  std::ifstream status("/proc/self/status");
  std::string key;
  long kib = 0;
  while (status >> key) {
    if (key == "VmSize:" && status >> kib) break;
    status.ignore(1 << 10, '\n');
  }
  return static_cast<long>(limit.rlim_cur) - (kib << 10);
}

void refuseWithoutRoomToStart() {
  if (plugin.handle) return;  // started already
  const long left = addressSpaceLeft();
  if (left < 0 || left >= kPetscStartupBytes) return;
  throw OutOfMemory(fmt::format(
      "starting PETSc and MPI for the linear solver takes about {} MiB of address space, and "
      "the limit leaves {} MiB; use solver=cholmod or umfpack, or more memory",
      kPetscStartupBytes >> 20, left >> 20));
}

}  // namespace

std::unique_ptr<LinearSolver> makePetscSolver(PetscMethod method) {
  refuseWithoutRoomToStart();
  // MUMPS and SuperLU_dist call BLAS like CHOLMOD and UMFPACK do: the buffer OpenBLAS would
  // retry forever is taken (or refused) first.
  reserveBlasWorkspace();
  loadOrThrow("the PETSc solvers are", "use solver=cholmod or umfpack, or ");
  return std::unique_ptr<LinearSolver>(plugin.make(static_cast<int>(method)));
}

void* petscPluginEntry(const char* name) {
  loadOrThrow("runs on several processes (MPI) are", "run on one process, or ");
  void* entry = dlsym(plugin.handle, name);
  if (!entry) throw std::runtime_error(std::string("the PETSc plugin lacks the entry ") + name);
  return entry;
}

namespace petsc {

void finalize() {
  if (plugin.finalize) plugin.finalize();
}

}  // namespace petsc

}  // namespace cc
