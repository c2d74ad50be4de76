// Loading of the PETSc backend plugin (src/parallel, library covcontact_petsc) and the process's
// one PETSc/MPI finalization. makePetscSolver (linear_solver.hpp) loads the plugin on first use.
#pragma once

namespace cc {

// The plugin's entry point `name` (loading the plugin on first use). Throws std::runtime_error
// saying why when the plugin cannot be loaded or lacks the entry.
void* petscPluginEntry(const char* name);

}  // namespace cc

namespace cc::petsc {

// PetscFinalize (and MPI_Finalize) if the plugin was loaded and initialized PETSc; call once,
// before the process exits. A no-op otherwise.
void finalize();

}  // namespace cc::petsc
