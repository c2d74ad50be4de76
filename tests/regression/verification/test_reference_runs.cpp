// Reference-aware runs: the deck's `reference` lines are checked when the model is built (errors
// name the line), sampled on every converged step, and `covcontact run` prints the errors and
// stores them in /verification of the results file.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/errors.hpp"
#include "deck/deck_parser.hpp"
#include "deck_runner.hpp"
#include "output/hdf5_io.hpp"
#include "verification/reference_tracker.hpp"

namespace cc::verification {
namespace {

const std::string kSourceDir = COVCONTACT_SOURCE_DIR;
const std::string kDeckDir = kSourceDir + "/input/verification/contact/";

// Two stacked blocks (matching 2 x 2 meshes, frictionless STS) compressed by a prescribed top
// displacement: a homogeneous uniaxial stress state, exactly representable by Hex8 elements.
std::string stackedBlocks(const std::string& references, double squeeze = 1e-6) {
  std::ostringstream deck;
  deck << R"(mesh "../../../meshes/patch_blocks.geo" W=1 T=0.5 nl=2 nu=2 nz=1
material elastic svk E=1000 nu=0.3
elements lower hex8 material=elastic
elements upper hex8 material=elastic
fix lower_bottom uz
fix lower_xmin ux
fix upper_xmin ux
fix lower_ymin uy
fix upper_ymin uy
prescribe upper_top uz "-)"
       << squeeze << R"(*t"
contact sts master=lower_top slave=upper_bottom eps_n=1e8 points=2 name=interface
)" << references
       << R"(
solve
  steps 2 dt=0.5
end
)";
  return deck.str();
}

// The recorded steps of an in-process run, fed to a tracker as the run command does.
std::vector<ReferenceResult> trackedResults(const test::DeckRun& run) {
  ReferenceTracker tracker(*run.model);
  for (const test::RecordedStep& step : run.steps) tracker.observe(step.record());
  return tracker.results();
}

TEST(ReferenceRuns, ValueAndTableErrorsAreMeasuredMinusReference) {
  // Uniaxial stress: F = E A d / (2 T) with the penalty in series (small strain, 1e-6).
  const double stiffness = 1000 * 1.0 / (2 * 0.5), penalty = 1e8, squeeze = 1e-6;
  const double force = squeeze / (1 / stiffness + 1 / penalty);
  const std::string references = fmt::format(
      "reference reaction:upper_top:z value={0:.17g}\n"
      "reference reaction:upper_top:z table (0,0) (1,{0:.17g})\n"
      "reference contact:interface:pressure_deviation value=0\n"
      "reference displacement:upper_top:z table (0.75,0) (2,0)\n",
      -force);
  const test::DeckRun run = test::runDeckText(stackedBlocks(references), kDeckDir + "inline.deck");
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed);
  const auto results = trackedResults(run);
  ASSERT_EQ(results.size(), 4u);
  const double measured = run.steps.back().setReaction("upper_top").z();
  EXPECT_EQ(results[0].kind, "value");
  EXPECT_EQ(results[0].samples.size(), 2u);
  EXPECT_EQ(results[0].samples.back().measured, measured);
  EXPECT_DOUBLE_EQ(results[0].error, measured + force);
  // The geometric nonlinearity of SVK at strain 1e-6: ~1e-6.
  EXPECT_LT(std::abs(results[0].relativeError), 1e-5);
  EXPECT_EQ(results[1].samples.size(), 2u);
  EXPECT_NEAR(results[1].samples.front().reference, -0.5 * force, 1e-12);
  EXPECT_LT(results[1].maxRelativeError, 1e-5);
  // Matching meshes under uniform pressure: every STS point carries the same pressure.
  EXPECT_LT(std::abs(results[2].error), 1e-9);
  EXPECT_TRUE(std::isnan(results[2].relativeError));  // reference 0: no relative error
  // Only the step at t = 1 lies in the table's range [0.75, 2]; the top moved by -squeeze.
  ASSERT_EQ(results[3].samples.size(), 1u);
  EXPECT_DOUBLE_EQ(results[3].samples.front().measured, -squeeze);
}

// Builds the model of `references` on the stacked blocks and returns the InputError's text.
std::string referenceError(const std::string& references) {
  try {
    const auto model = buildModel(parseDeckText(stackedBlocks(references), kDeckDir + "bad.deck"));
    ReferenceTracker tracker(*model);
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

TEST(ReferenceRuns, BadReferencesAreInputErrorsAtTheirLine) {
  const std::string line = "bad.deck:12";  // the first reference line of stackedBlocks
  auto expectError = [&](const std::string& reference, const std::string& expected) {
    const std::string message = referenceError(reference);
    EXPECT_NE(message.find(line), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  };
  expectError("reference contact:interface:fource:z value=1", "expected reaction:SET");
  expectError("reference contact:nopair:force:z value=1", "no contact pair named 'nopair'");
  expectError("reference reaction:upper:z value=1", "no reaction is reported for 'upper'");
  expectError("reference displacement:nowhere:x value=1", "no node set named 'nowhere'");
  expectError("reference contact:interface:radius analytic hertz_cone R=1",
              "unknown analytic solution");
  expectError("reference contact:interface:radius analytic hertz_sphere E=1 nu=0.3",
              "hertz_sphere needs the parameter R=NUMBER");
  expectError("reference contact:interface:radius analytic hertz_sphere R=1 E=1 nu=0.3 mu=0.2",
              "unknown parameter 'mu' of hertz_sphere");
  expectError("reference contact:interface:half_width analytic hertz_sphere R=1 E=1 nu=0.3",
              "hertz_sphere gives no value for 'contact:interface:half_width'");
  expectError(
      "reference contact:interface:force:z analytic hertz_sphere R=1 E=1 nu=0.3 "
      "probe1_z=0.5 probe2_z=-0.3",
      "no mesh node at the probe point (0, 0, -0.3)");
  expectError(
      "reference contact:interface:force:z analytic hertz_sphere R=1 E=1 nu=0.3 probe2_z=-0.5",
      "give probe1_z");
  expectError(
      "reference contact:interface:stick_radius analytic cattaneo_mindlin_sphere R=1 E=1 "
      "nu=0.3 mu=0.2",
      "needs elastically similar bodies");
  EXPECT_EQ(referenceError("reference contact:interface:stick_radius analytic "
                           "cattaneo_mindlin_sphere R=1 E=1 nu=0.3 E1=1 nu1=0.3 mu=0.2"),
            "no error");
}

// The command prints the error table and adds /verification to the results file.
TEST(ReferenceRuns, RunCommandPrintsAndStoresTheErrors) {
  const std::filesystem::path dir =
      std::filesystem::path(COVCONTACT_BINARY_DIR) / "verification_cli";
  std::filesystem::create_directories(dir);
  const std::filesystem::path deck = dir / "stacked.deck";
  std::string text = stackedBlocks("reference reaction:upper_top:z value=-0.25\n");
  const std::string meshLine = "\"../../../meshes/patch_blocks.geo\"";
  text.replace(text.find(meshLine), meshLine.size(),
               "\"" + kSourceDir + "/meshes/patch_blocks.geo\"");
  std::ofstream(deck) << text;
  const std::string results = (dir / "stacked.h5").string(),
                    printed = (dir / "stdout.txt").string();
  const std::string command = std::string(COVCONTACT_BINARY_DIR) + "/src/app/covcontact run " +
                              deck.string() + " -o " + results + " > " + printed;
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::stringstream output;
  output << std::ifstream(printed).rdbuf();
  EXPECT_NE(output.str().find("reaction:upper_top:z (value)"), std::string::npos) << output.str();
  EXPECT_NE(output.str().find("Newton iterations"), std::string::npos) << output.str();

  h5::QuietErrors quiet;
  const h5::File file(H5Fopen(results.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  ASSERT_TRUE(file.valid());
  const h5::FileRef ref{file.get(), results};
  const h5::Group group = h5::openGroup(ref, file.get(), "verification/reference_1");
  EXPECT_EQ(h5::readStringAttribute(ref, group.get(), "quantity"), "reaction:upper_top:z");
  const double measured = h5::readNumberAttribute(ref, group.get(), "measured");
  EXPECT_DOUBLE_EQ(h5::readNumberAttribute(ref, group.get(), "error"), measured + 0.25);
  EXPECT_EQ(h5::readDoubles(ref, group.get(), "time").rows(), 2);
  const h5::Group summary = h5::openGroup(ref, file.get(), "verification");
  EXPECT_GT(h5::readNumberAttribute(ref, summary.get(), "newton_iterations"), 0);
  EXPECT_GT(h5::readNumberAttribute(ref, summary.get(), "wall_seconds"), 0);
}

}  // namespace
}  // namespace cc::verification
