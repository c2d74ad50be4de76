// Bad input that shows only during a run (issue 7): an expression that is not finite at a later
// time stops the run with exit code 2 at the deck line, keeping every converged step in a
// results file that is closed with the reason.
#include <gtest/gtest.h>

#include "output/results_reader.hpp"
#include "stress_support.hpp"

namespace cc::test {
namespace {

TEST(BadInput, ExpressionThatIsNotFiniteAtRunTimeStopsWithExitCode2KeepingTheFirstStep) {
  const std::string directory = scratchDirectory("expression_not_finite");
  const std::string deck = stressDeck("expression_not_finite");
  EXPECT_EQ(runCovcontact("check '" + deck + "'", directory).exitCode, kExitOk);
  const CommandResult result =
      runCovcontact("run -q --threads 1 '" + deck + "' -o run.h5", directory);
  EXPECT_EQ(result.exitCode, kExitInput) << result.error;
  EXPECT_NE(result.error.find("expression_not_finite.deck:10:"), std::string::npos) << result.error;
  EXPECT_NE(result.error.find("is not finite at t = 2"), std::string::npos) << result.error;
  // ... and says that the converged step is kept (it did not).
  EXPECT_NE(result.error.find("the 1 converged steps are kept in run.h5"), std::string::npos)
      << result.error;
  const ResultsReader reader(directory + "/run.h5");
  ASSERT_EQ(reader.steps().size(), 1u);
  EXPECT_EQ(reader.steps()[0].time, 1.0);
  EXPECT_EQ(reader.stringAttribute("/summary", "outcome"), "input error");
  EXPECT_EQ(reader.numberAttribute("/summary", "steps"), 1.0);
}

}  // namespace
}  // namespace cc::test
