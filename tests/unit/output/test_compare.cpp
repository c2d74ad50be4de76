// compareRuns on pairs of synthetic runs: identical runs match; a changed iteration count, a force
// off by 1e-6 relative, a missing step or an unknown field are reported at the right step/field.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <limits>

#include "output/compare.hpp"
#include "output/results_writer.hpp"
#include "synthetic_run.hpp"

namespace cc::test {
namespace {

namespace fs = std::filesystem;

constexpr int kSteps = 3;
constexpr double kPerturbation = 1e-6;  // relative, 100x above the default rtol of 1e-8

using Modifier = std::function<void(SyntheticStep&)>;

class Compare : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("covcontact_compare_" +
                  std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(directory_);
    fs::create_directories(directory_);
    reference_ = writeRun("reference.h5", kSteps, [](SyntheticStep&) {});
  }
  void TearDown() override { fs::remove_all(directory_); }

  std::string writeRun(const std::string& name, int steps, const Modifier& modify) {
    const std::string path = (directory_ / name).string();
    const SyntheticMesh mesh = makeSyntheticMesh();
    OutputSelection selection;
    selection.xdmf = false;
    selection.csv = false;
    ResultsWriter writer;
    writer.open(path, syntheticRunInfo(), mesh.mesh, selection);
    for (int number = 1; number <= steps; ++number) {
      SyntheticStep step;
      fillSyntheticStep(mesh.mesh, number, step);
      modify(step);
      writer.writeStep(step.record);
    }
    writer.close({"completed", steps, 0, 0, 0, ""});
    return path;
  }

  fs::path directory_;
  std::string reference_;
};

TEST_F(Compare, IdenticalRunsMatch) {
  const std::string run = writeRun("run.h5", kSteps, [](SyntheticStep&) {});
  const CompareResult result = compareRuns(run, reference_, {});
  EXPECT_TRUE(result.match) << result.report;
  EXPECT_EQ(result.mismatchCount, 0);
  EXPECT_NE(result.report.find("MATCH: 3 steps agree"), std::string::npos) << result.report;
}

TEST_F(Compare, ChangedIterationCountIsReportedAtItsStep) {
  const std::string run = writeRun("run.h5", kSteps, [](SyntheticStep& step) {
    if (step.record.step == 2) step.record.iterations += 1;
  });
  const CompareResult result = compareRuns(run, reference_, {});
  ASSERT_FALSE(result.match);
  ASSERT_EQ(result.mismatchCount, 1) << result.report;
  EXPECT_EQ(result.reported[0].step, 2);
  EXPECT_EQ(result.reported[0].field, "iterations");
  SyntheticStep expected;
  fillSyntheticStep(makeSyntheticMesh().mesh, 2, expected);
  EXPECT_EQ(result.reported[0].runValue, expected.record.iterations + 1);
  EXPECT_EQ(result.reported[0].referenceValue, expected.record.iterations);
  EXPECT_NE(result.report.find("iterations"), std::string::npos) << result.report;
}

TEST_F(Compare, SetReactionOffByOneInAMillionIsReportedWithSetAndAxis) {
  const std::string run = writeRun("run.h5", kSteps, [](SyntheticStep& step) {
    if (step.record.step == 3) step.record.setReactions[1].second.z() *= 1 + kPerturbation;
  });
  const CompareResult result = compareRuns(run, reference_, {});
  ASSERT_EQ(result.mismatchCount, 1) << result.report;
  const Mismatch& mismatch = result.reported[0];
  EXPECT_EQ(mismatch.step, 3);
  EXPECT_EQ(mismatch.field, "set_reactions");
  EXPECT_EQ(mismatch.index, "top.z");
  // |a - b| / max(|a|, |b|) = p / (1 + p); the subtraction loses about eps / p relative accuracy.
  const double roundoff = std::numeric_limits<double>::epsilon() / kPerturbation;
  EXPECT_NEAR(mismatch.relativeDifference, kPerturbation / (1 + kPerturbation),
              4 * roundoff * kPerturbation);
  EXPECT_NE(result.report.find("top.z"), std::string::npos) << result.report;
}

TEST_F(Compare, ContactForceOffByOneInAMillionIsReportedWithPairAndAxis) {
  const std::string run = writeRun("run.h5", kSteps, [](SyntheticStep& step) {
    if (step.record.step == 1) step.record.contact[0].totalForce.x() *= 1 - kPerturbation;
  });
  const CompareResult result = compareRuns(run, reference_, {});
  ASSERT_EQ(result.mismatchCount, 1) << result.report;
  EXPECT_EQ(result.reported[0].step, 1);
  EXPECT_EQ(result.reported[0].field, "contact/pair1/total_force");
  EXPECT_EQ(result.reported[0].index, "x");
}

TEST_F(Compare, DifferenceWithinRtolMatches) {
  const std::string run = writeRun("run.h5", kSteps, [](SyntheticStep& step) {
    step.record.setReactions[0].second *= 1 + 1e-2 * CompareOptions{}.rtol;
  });
  EXPECT_TRUE(compareRuns(run, reference_, {}).match);
}

TEST_F(Compare, AbsoluteFloorAbsorbsRoundoffNearZeroUnlessDisabled) {
  // The reference holds an exact 0; the run has roundoff 1e-3 * floor there (floor = 1e-12 max).
  const auto zeroed = [](double roundoffFactor) {
    return [roundoffFactor](SyntheticStep& step) {
      double largest = 0;
      for (const auto& [name, force] : step.record.setReactions)
        largest = std::max(largest, force.cwiseAbs().maxCoeff());
      step.record.setReactions[0].second.x() = roundoffFactor * kDefaultAtolFactor * largest;
    };
  };
  const std::string reference = writeRun("zero_reference.h5", kSteps, zeroed(0));
  const std::string run = writeRun("zero_run.h5", kSteps, zeroed(1e-3));
  EXPECT_TRUE(compareRuns(run, reference, {}).match);
  CompareOptions strict;
  strict.atol = 0;
  const CompareResult result = compareRuns(run, reference, strict);
  EXPECT_EQ(result.mismatchCount, kSteps) << result.report;
}

TEST_F(Compare, DisplacementIsComparedOnlyWhenAsked) {
  const std::string run = writeRun("run.h5", kSteps, [](SyntheticStep& step) {
    if (step.record.step == 2) step.displacement(1, 7) *= 1 + kPerturbation;
  });
  EXPECT_TRUE(compareRuns(run, reference_, {}).match);
  CompareOptions options;
  options.fields = {"displacement"};
  const CompareResult result = compareRuns(run, reference_, options);
  ASSERT_EQ(result.mismatchCount, 1) << result.report;
  EXPECT_EQ(result.reported[0].step, 2);
  EXPECT_EQ(result.reported[0].field, "displacement");
  EXPECT_EQ(result.reported[0].index, "[7, y]");
}

TEST_F(Compare, WildcardFieldCoversEveryContactPair) {
  const std::string run = writeRun("run.h5", kSteps, [](SyntheticStep& step) {
    if (step.record.step == 3) step.record.contact[1].gap(1) *= 1 + kPerturbation;
  });
  CompareOptions options;
  options.fields = {"contact/*/gap"};
  const CompareResult result = compareRuns(run, reference_, options);
  ASSERT_EQ(result.mismatchCount, 1) << result.report;
  EXPECT_EQ(result.reported[0].step, 3);
  EXPECT_EQ(result.reported[0].field, "contact/pair2/gap");
  EXPECT_EQ(result.reported[0].index, "[1]");
}

TEST_F(Compare, NanMatchesOnlyNan) {
  // A contact point that is not projected has no gap: NaN in both runs is agreement.
  const auto unprojected = [](SyntheticStep& step) {
    step.record.contact[0].gap(2) = std::numeric_limits<double>::quiet_NaN();
  };
  const std::string reference = writeRun("nan_reference.h5", kSteps, unprojected);
  const std::string run = writeRun("nan_run.h5", kSteps, unprojected);
  CompareOptions options;
  options.fields = {"contact/*/gap"};
  EXPECT_TRUE(compareRuns(run, reference, options).match);
  const CompareResult result = compareRuns(run, reference_, options);
  EXPECT_EQ(result.mismatchCount, kSteps) << result.report;
  EXPECT_EQ(result.reported[0].index, "[2]");
}

TEST_F(Compare, MissingStepAndUnknownFieldAreMismatches) {
  const std::string shorter = writeRun("short.h5", kSteps - 1, [](SyntheticStep&) {});
  const CompareResult result = compareRuns(shorter, reference_, {});
  ASSERT_EQ(result.mismatchCount, 2) << result.report;
  EXPECT_EQ(result.reported[0].field, "step count");
  EXPECT_EQ(result.reported[1].step, kSteps);
  EXPECT_EQ(result.reported[1].index, "missing in run");

  CompareOptions typo;
  typo.fields = {"displacment"};
  const CompareResult unknown = compareRuns(reference_, reference_, typo);
  ASSERT_EQ(unknown.mismatchCount, 1) << unknown.report;
  EXPECT_EQ(unknown.reported[0].index, "not found in either file");
}

TEST_F(Compare, ReportListsOnlyTheFirstMismatchesButCountsAll) {
  const std::string run = writeRun("run.h5", kSteps, [](SyntheticStep& step) {
    step.record.iterations += 1;
    step.record.contact[1].totalForce *= 2;
  });
  CompareOptions options;
  options.maxReported = 2;
  const CompareResult result = compareRuns(run, reference_, options);
  // 3 iteration counts, pair1 untouched, pair2: 3 components in 3 steps.
  EXPECT_EQ(result.mismatchCount, 3 + 3 * 3) << result.report;
  EXPECT_EQ(result.reported.size(), 2u);
  EXPECT_NE(result.report.find("12 difference(s), first 2 shown"), std::string::npos)
      << result.report;
}

TEST_F(Compare, UnreadableFileIsAnOutputError) {
  EXPECT_THROW(compareRuns((directory_ / "absent.h5").string(), reference_, {}), OutputError);
}

}  // namespace
}  // namespace cc::test
