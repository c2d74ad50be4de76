// The BLAS kernels of a run (app/blas_environment.hpp): the core type follows from the CPU's
// instruction sets, and a user's own OPENBLAS_CORETYPE is kept.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "app/blas_environment.hpp"

namespace cc::app {
namespace {

TEST(BlasEnvironment, CoreTypeFollowsTheInstructionSets) {
  EXPECT_STREQ(openblasCoreType({.avx2Fma = true}), "Haswell");
  EXPECT_EQ(openblasCoreType({.avx2Fma = false}), nullptr);
}

TEST(BlasEnvironment, AUsersCoreTypeIsKeptAndAMissingOneIsThisCpus) {
  const char* before = std::getenv("OPENBLAS_CORETYPE");
  const std::string saved = before ? before : "";
  setenv("OPENBLAS_CORETYPE", "Sandybridge", 1);
  EXPECT_FALSE(setBlasEnvironment());
  EXPECT_STREQ(std::getenv("OPENBLAS_CORETYPE"), "Sandybridge");
  unsetenv("OPENBLAS_CORETYPE");
  const char* expected = openblasCoreType(cpuFeatures());
  EXPECT_EQ(setBlasEnvironment(), expected != nullptr);
  const char* set = std::getenv("OPENBLAS_CORETYPE");
  EXPECT_EQ(set ? std::string(set) : std::string(), expected ? std::string(expected) : "");
  if (before) {
    setenv("OPENBLAS_CORETYPE", saved.c_str(), 1);
  } else {
    unsetenv("OPENBLAS_CORETYPE");
  }
}

}  // namespace
}  // namespace cc::app
