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

}  // namespace

std::unique_ptr<LinearSolver> makePetscSolver(PetscMethod method) {
  std::call_once(loadOnce, load);
  if (!loadError.empty()) {
    throw std::runtime_error("the PETSc solvers are not available (" + loadError +
                             "); use solver=cholmod or umfpack, or install PETSc with "
                             "scripts/install-deps.sh and rebuild");
  }
  return std::unique_ptr<LinearSolver>(plugin.make(static_cast<int>(method)));
}

namespace petsc {

void finalize() {
  if (plugin.finalize) plugin.finalize();
}

}  // namespace petsc

}  // namespace cc
