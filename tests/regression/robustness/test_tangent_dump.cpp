// `covcontact run --dump-tangent STEP:ITER[:ATTEMPT]` (issue 14): the system of a later attempt
// of a step can be written too, so that a stalled retry can be examined, not only the first
// attempt. Checked on a step whose first attempt fails and is cut back, against what a cut-back
// does to the first Newton system: same configuration, so the same tangent, and a load linear in
// time, so half the right-hand side.
#include <gtest/gtest.h>

#include <filesystem>

#include "solver/tangent_dump.hpp"
#include "stress_support.hpp"

namespace cc::test {
namespace {

TEST(TangentDump, ALaterAttemptOfAStepIsWrittenBesideTheFirst) {
  // held_by_contact_only: step 1 (dt = 0.5) is singular, cut back once to dt = 0.25, singular
  // again. Both first iterations start from the undeformed state (no internal force there).
  const std::string directory = scratchDirectory("tangent_dump_attempts");
  const CommandResult result =
      runCovcontact("run -q --threads 1 '" + stressDeck("held_by_contact_only") +
                        "' -o run.h5 --dump-tangent 1:1 --dump-tangent 1:1:1 --dump-tangent 1:1:2",
                    directory);
  EXPECT_EQ(result.exitCode, kExitSingular) << result.error;
  const TangentDump first = readTangentDump(directory + "/run_tangent_1_1");
  const TangentDump cutBack = readTangentDump(directory + "/run_tangent_1_1_a1");
  EXPECT_FALSE(std::filesystem::exists(directory + "/run_tangent_1_1_a2"));  // no third attempt
  ASSERT_EQ(first.matrix.rows(), cutBack.matrix.rows());
  ASSERT_GT(first.matrix.norm(), 0);
  EXPECT_EQ((first.matrix - cutBack.matrix).norm(), 0);
  // rhs = f_ext(t) - f_int(X): the internal force of the undeformed state is round-off of the
  // stiffness times the coordinates, eps |K| |X| ~ 2e-16 x 2e4 x 10 = 4e-11 per equation, which
  // the halving leaves at half its size (|rhs| ~ 30). The wrong attempt's rhs differs by 0.5.
  ASSERT_GT(first.rhs.norm(), 0);
  EXPECT_LT((cutBack.rhs - 0.5 * first.rhs).norm(), 1e-9 * first.rhs.norm());
}

TEST(TangentDump, AMalformedSelectionIsAUsageError) {
  const std::string directory = scratchDirectory("tangent_dump_malformed");
  for (const std::string selection : {"1:1:x", "1:1:-1", "0:1", "1:1:1:1"}) {
    const CommandResult result = runCovcontact(
        "run -q '" + stressDeck("held_by_contact_only") + "' --dump-tangent " + selection,
        directory);
    EXPECT_EQ(result.exitCode, kExitUsage) << selection;
    EXPECT_NE(result.error.find("expected STEP:ITER or STEP:ITER:ATTEMPT"), std::string::npos)
        << result.error;
  }
}

}  // namespace
}  // namespace cc::test
