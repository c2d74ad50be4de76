// ResultsWriter behaviour beyond the round trip: field selection, runs without contact, errors that
// name the file and operation, long deck texts, and files left behind without close().
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "output/results_reader.hpp"
#include "output/results_writer.hpp"
#include "output/xdmf_writer.hpp"
#include "synthetic_run.hpp"

namespace cc::test {
namespace {

namespace fs = std::filesystem;

class Writer : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("covcontact_writer_" +
                  std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(directory_);
    fs::create_directories(directory_);
    mesh_ = makeSyntheticMesh();
  }
  void TearDown() override { fs::remove_all(directory_); }

  std::string pathOf(const std::string& name) const { return (directory_ / name).string(); }

  fs::path directory_;
  SyntheticMesh mesh_;
};

TEST_F(Writer, WritesOnlySelectedFields) {
  OutputSelection selection;
  selection.reaction = false;
  selection.stress = false;
  selection.contact = false;
  selection.csv = false;
  selection.xdmf = false;
  const std::string path = pathOf("selected.h5");
  ResultsWriter writer;
  writer.open(path, syntheticRunInfo(), mesh_.mesh, selection);
  SyntheticStep step;
  fillSyntheticStep(mesh_.mesh, 1, step);
  writer.writeStep(step.record);
  writer.close({"completed", 1, 3, 0, 0.1, ""});

  const ResultsReader reader(path);
  EXPECT_TRUE(reader.hasDataset("/steps/000001/displacement"));
  EXPECT_FALSE(reader.hasDataset("/steps/000001/reaction"));
  EXPECT_FALSE(reader.hasDataset("/steps/000001/stress"));
  EXPECT_FALSE(reader.hasGroup("/steps/000001/contact"));
  EXPECT_FALSE(fs::exists(xdmfPathFor(path)));
  EXPECT_FALSE(fs::exists(csvPathFor(path)));
}

TEST_F(Writer, RunWithoutContactHasNoContactGroupOrPointClouds) {
  const std::string path = pathOf("nocontact.h5");
  ResultsWriter writer;
  writer.open(path, syntheticRunInfo(), mesh_.mesh);
  SyntheticStep step;
  fillSyntheticStep(mesh_.mesh, 1, step);
  step.record.contact.clear();
  writer.writeStep(step.record);
  writer.close({"completed", 1, 3, 0, 0.1, ""});

  EXPECT_FALSE(ResultsReader(path).hasGroup("/steps/000001/contact"));
  std::ifstream xdmf(xdmfPathFor(path));
  const std::string text((std::istreambuf_iterator<char>(xdmf)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("Polyvertex"), std::string::npos);
  EXPECT_NE(text.find("Name=\"base\""), std::string::npos);
}

TEST_F(Writer, MissingDirectoryIsReportedWithThePathBeforeAnythingIsCreated) {
  const std::string path = pathOf("no/such/dir/run.h5");
  try {
    checkOutputWritable(path);
    FAIL() << "expected OutputError";
  } catch (const OutputError& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("does not exist"), std::string::npos) << error.what();
  }
  ResultsWriter writer;
  EXPECT_THROW(writer.open(path, syntheticRunInfo(), mesh_.mesh), OutputError);
  EXPECT_FALSE(writer.isOpen());
}

TEST_F(Writer, UnwritableSidecarStopsOpenBeforeTheResultsFileIsCreated) {
  const std::string path = pathOf("sidecar.h5");
  fs::create_directories(xdmfPathFor(path));  // a directory where the XDMF file should go
  ResultsWriter writer;
  try {
    writer.open(path, syntheticRunInfo(), mesh_.mesh);
    FAIL() << "expected OutputError";
  } catch (const OutputError& error) {
    EXPECT_NE(std::string(error.what()).find(xdmfPathFor(path)), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("is a directory"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(path));
}

TEST_F(Writer, SelectedFieldThatIsMissingOrMisSizedIsRejected) {
  ResultsWriter writer;
  writer.open(pathOf("missing.h5"), syntheticRunInfo(), mesh_.mesh);
  SyntheticStep step;
  fillSyntheticStep(mesh_.mesh, 1, step);
  step.record.displacement = nullptr;
  EXPECT_THROW(writer.writeStep(step.record), std::invalid_argument);
  fillSyntheticStep(mesh_.mesh, 1, step);
  step.record.contact[0].gap.resize(2);
  EXPECT_THROW(writer.writeStep(step.record), std::invalid_argument);
}

TEST_F(Writer, HdfFailureNamesFileAndOperation) {
  const std::string path = pathOf("twice.h5");
  ResultsWriter writer;
  writer.open(path, syntheticRunInfo(), mesh_.mesh);
  SyntheticStep step;
  fillSyntheticStep(mesh_.mesh, 1, step);
  writer.writeStep(step.record);
  try {
    writer.writeStep(step.record);  // the group /steps/000001 exists already
    FAIL() << "expected OutputError";
  } catch (const OutputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("creating group '000001'"), std::string::npos) << message;
  }
}

TEST_F(Writer, LongDeckTextIsKeptWhole) {
  // Far beyond the 64 KiB limit of an attribute stored in an object header.
  constexpr size_t kDeckBytes = 300 * 1024;
  RunInfo info = syntheticRunInfo();
  info.deckText.assign(kDeckBytes, 'x');
  info.deckText += "\nend\n";
  const std::string path = pathOf("long.h5");
  ResultsWriter writer;
  writer.open(path, info, mesh_.mesh);
  writer.close({"completed", 0, 0, 0, 0, ""});
  EXPECT_EQ(ResultsReader(path).stringAttribute("/", "deck_text"), info.deckText);
}

TEST_F(Writer, FileLeftWithoutCloseKeepsItsSteps) {
  const std::string path = pathOf("unclosed.h5");
  {
    ResultsWriter writer;
    writer.open(path, syntheticRunInfo(), mesh_.mesh);
    for (int stepNumber = 1; stepNumber <= 2; ++stepNumber) {
      SyntheticStep step;
      fillSyntheticStep(mesh_.mesh, stepNumber, step);
      writer.writeStep(step.record);
    }
  }
  const ResultsReader reader(path);
  ASSERT_EQ(reader.steps().size(), 2u);
  EXPECT_EQ(reader.steps()[1].step, 2);
  EXPECT_FALSE(reader.hasGroup("/summary"));
}

TEST_F(Writer, XdmfAppendedInPlaceEqualsXdmfReplacedAtomically) {
  const std::vector<XdmfBlock> blocks = {{"base", "Hexahedron", 4, 8, "/mesh/base", 0}};
  const auto writeSteps = [&](const std::string& name, size_t atomicRewriteLimit) {
    XdmfWriter xdmf(pathOf(name), "run.h5", 18, 4, blocks, atomicRewriteLimit);
    for (int step = 1; step <= 3; ++step)
      xdmf.appendStep({step, 0.5 * step, true, true, false, {{"pair1", 5}}});
    std::ifstream file(pathOf(name));
    return std::string((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  };
  const std::string atomic = writeSteps("atomic.xdmf", kDefaultAtomicRewriteLimit);
  constexpr size_t kOneStepFits = 3000;  // header, one step (about 2 KiB) and closing tags
  const std::string inPlace = writeSteps("in_place.xdmf", kOneStepFits);
  EXPECT_EQ(inPlace, atomic);
  EXPECT_GT(atomic.size(), kOneStepFits);  // so steps 2 and 3 really were appended in place
  EXPECT_FALSE(fs::exists(pathOf("atomic.xdmf.tmp")));
}

TEST_F(Writer, ReaderRejectsMissingAndForeignFiles) {
  const std::string missing = pathOf("missing.h5");
  try {
    ResultsReader reader(missing);
    FAIL() << "expected OutputError";
  } catch (const OutputError& error) {
    EXPECT_NE(std::string(error.what()).find(missing), std::string::npos) << error.what();
  }
  const std::string foreign = pathOf("foreign.h5");
  H5Fclose(H5Fcreate(foreign.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
  EXPECT_THROW(ResultsReader reader(foreign), OutputError);
}

}  // namespace
}  // namespace cc::test
