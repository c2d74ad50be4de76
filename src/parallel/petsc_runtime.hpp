// PETSc (and with it MPI) for the whole process: initialized once, on the first use of a PETSc
// backend, and finalized once by the command before it exits. A run with the direct solvers
// never starts MPI (no start-up cost, no MPI progress threads); a serial run needs no mpirun
// (Open MPI's singleton initialization). Only this module (the covcontact_petsc plugin)
// includes PETSc or MPI headers; element, material and contact code never sees them.
#pragma once

namespace cc::petsc {

// Initializes PETSc (and MPI, if nobody has) unless done already. PETSc's own signal handlers
// stay off: `covcontact run` handles SIGINT/SIGTERM itself.
void ensureInitialized();
bool initialized();
// PetscFinalize (which finalizes MPI when PETSc started it); a no-op when never initialized.
void finalize();

}  // namespace cc::petsc
