// dlopen of the PETSc plugin, see petsc_loader.hpp. The plugin is found at the path the build
// compiled in (COVCONTACT_PETSC_MODULE), unless the environment variable of the same name names
// another one.
#include "solver/petsc_loader.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <string>

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

}  // namespace

std::unique_ptr<LinearSolver> makePetscSolver(PetscMethod method) {
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
