// For a gtest program that uses the PETSc plugin: PETSc and MPI are finalized once, after every
// test of the program. Include it in one source file of the program.
#pragma once

#include <gtest/gtest.h>

#include "solver/petsc_loader.hpp"

namespace cc::test {

class PetscEnvironment : public ::testing::Environment {
 public:
  void TearDown() override { petsc::finalize(); }
};

inline const auto* const petscEnvironment =
    ::testing::AddGlobalTestEnvironment(new PetscEnvironment);

}  // namespace cc::test
