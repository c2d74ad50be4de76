// Loading of the PETSc backend plugin (src/parallel, library covcontact_petsc) and the process's
// one PETSc/MPI finalization. makePetscSolver (linear_solver.hpp) loads the plugin on first use.
#pragma once

namespace cc::petsc {

// PetscFinalize (and MPI_Finalize) if the plugin was loaded and initialized PETSc; call once,
// before the process exits. A no-op otherwise.
void finalize();

}  // namespace cc::petsc
