// Round trip of a synthetic 3-step run: everything ResultsWriter wrote is read back with the raw
// HDF5 C API (not the module's reader) and compared exactly; also the CSV and XDMF sidecars.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "output/results_layout.hpp"
#include "output/results_mesh.hpp"
#include "roundtrip_fixture.hpp"

namespace cc::test {
namespace {

class RoundTrip : public ::testing::Test {
 protected:
  void SetUp() override {
    run_ = &roundTripRun();
    file_ = H5Fopen(run_->h5Path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(file_, 0) << run_->h5Path;
  }
  void TearDown() override {
    if (file_ >= 0) H5Fclose(file_);
  }

  // Compares an N x 3 (or E x 6) dataset with the column-major 3 x N (6 x E) matrix it came from.
  template <class Matrix>
  void expectTable(const std::string& path, const Matrix& expected) {
    const RawArray stored = readRaw(file_, path);
    ASSERT_EQ(stored.dims.size(), 2u) << path;
    ASSERT_EQ(stored.dims[0], static_cast<hsize_t>(expected.cols())) << path;
    ASSERT_EQ(stored.dims[1], static_cast<hsize_t>(expected.rows())) << path;
    for (Eigen::Index col = 0; col < expected.cols(); ++col)
      for (Eigen::Index row = 0; row < expected.rows(); ++row)
        ASSERT_EQ(stored.values[static_cast<size_t>(col * expected.rows() + row)],
                  static_cast<double>(expected(row, col)))
            << path << " [" << col << ", " << row << "]";
  }

  template <class Vector>
  void expectVector(const std::string& path, const Vector& expected) {
    const RawArray stored = readRaw(file_, path);
    ASSERT_EQ(stored.dims.size(), 1u) << path;
    ASSERT_EQ(stored.dims[0], static_cast<hsize_t>(expected.size())) << path;
    for (Eigen::Index i = 0; i < expected.size(); ++i)
      ASSERT_EQ(stored.values[static_cast<size_t>(i)], static_cast<double>(expected(i)))
          << path << " [" << i << "]";
  }

  const RoundTripRun* run_ = nullptr;
  hid_t file_ = H5I_INVALID_HID;
};

TEST_F(RoundTrip, RootAttributesHoldDeckAndCommandLine) {
  const RunInfo info = syntheticRunInfo();
  EXPECT_EQ(readRawStringAttribute(file_, "/", "deck_text").at(0), info.deckText);
  EXPECT_EQ(readRawStringAttribute(file_, "/", "command_line").at(0), info.commandLine);
  EXPECT_EQ(readRawStringAttribute(file_, "/", "title").at(0), info.title);
  EXPECT_EQ(readRawStringAttribute(file_, "/", "deck_path").at(0), info.deckPath);
  EXPECT_EQ(readRawStringAttribute(file_, "/", "format").at(0), layout::kFormatName);
  EXPECT_EQ(readRawNumberAttribute(file_, "/", "format_version"), layout::kFormatVersion);
}

TEST_F(RoundTrip, MeshIsStoredOnce) {
  const Mesh& mesh = run_->mesh.mesh;
  expectTable("/mesh/coordinates", mesh.coordinates);
  EXPECT_EQ(readRawStringAttribute(file_, "/mesh/blocks", "names"),
            (std::vector<std::string>{"base", "cap27", "shell18"}));
  // The cell type names of the file format (docs/output-format.md), spelled here so that a
  // change of toString(CellType) that would change the format fails.
  const std::map<std::string, std::string> expectedCellType = {
      {"base", "Hex8"}, {"cap27", "Hex27"}, {"shell18", "Hex18"}};
  for (const ElementBlock& block : mesh.blocks) {
    const std::string path = "/mesh/blocks/" + block.name;
    const RawArray stored = readRaw(file_, path + "/connectivity");
    ASSERT_EQ(stored.dims, (std::vector<hsize_t>{static_cast<hsize_t>(block.connectivity.rows()),
                                                 static_cast<hsize_t>(block.connectivity.cols())}));
    for (Eigen::Index i = 0; i < block.connectivity.size(); ++i)
      EXPECT_EQ(stored.values[static_cast<size_t>(i)], block.connectivity.data()[i]);
    EXPECT_EQ(readRawStringAttribute(file_, path, "cell_type").at(0),
              expectedCellType.at(block.name));
  }
  EXPECT_EQ(readRawNumberAttribute(file_, "/mesh/blocks/cap27", "first_element"), 4);
  EXPECT_EQ(readRawNumberAttribute(file_, "/mesh/blocks/shell18", "first_element"), 5);
  for (const auto& [name, set] : mesh.nodeSets)
    EXPECT_EQ(readRawInts(file_, "/mesh/node_sets/" + layout::linkName(name) + "/nodes"),
              set.nodes);
  const FaceSet& faces = mesh.faceSets.at("base_top");
  const std::vector<int> stored = readRawInts(file_, "/mesh/face_sets/base_top/connectivity");
  EXPECT_EQ(stored, std::vector<int>(faces.connectivity.data(),
                                     faces.connectivity.data() + faces.connectivity.size()));
  EXPECT_EQ(readRawInts(file_, "/mesh/face_sets/base_top/owner_element"), faces.ownerElement);
}

TEST_F(RoundTrip, VisualConnectivityFollowsVtkOrder) {
  // Hex18 is drawn by its 8 corners: bottom corners 0-3 and top corners 9-12 of the stored row.
  const std::vector<int> corners = readRawInts(file_, "/mesh/blocks/shell18/visual_connectivity");
  const Connectivity& shell = run_->mesh.mesh.blocks[2].connectivity;
  EXPECT_EQ(corners, (std::vector<int>{shell(0, 0), shell(0, 1), shell(0, 2), shell(0, 3),
                                       shell(0, 9), shell(0, 10), shell(0, 11), shell(0, 12)}));
  const std::vector<int> hex27 = readRawInts(file_, "/mesh/blocks/cap27/visual_connectivity");
  EXPECT_EQ(hex27.size(), 27u);  // positions are checked in ParaView itself (check_xdmf.py)
}

TEST_F(RoundTrip, EveryStepRoundTripsExactly) {
  for (int step = 1; step <= kRoundTripSteps; ++step) {
    SCOPED_TRACE("step " + std::to_string(step));
    SyntheticStep expected;
    roundTripStep(step, expected);
    const std::string group = layout::stepGroupPath(step);
    EXPECT_EQ(readRawNumberAttribute(file_, group, "time"), expected.record.time);
    EXPECT_EQ(readRawNumberAttribute(file_, group, "iterations"), expected.record.iterations);
    EXPECT_EQ(readRawNumberAttribute(file_, group, "cutbacks"), expected.record.cutbacks);
    expectTable(group + "/displacement", expected.displacement);
    expectTable(group + "/reaction", expected.reaction);
    expectTable(group + "/stress", expected.stress);
    Eigen::Matrix3Xd setForces(3, 3);
    std::vector<std::string> setNames;
    for (const auto& [name, force] : expected.record.setReactions) {
      setForces.col(static_cast<Eigen::Index>(setNames.size())) = force;
      setNames.push_back(name);
    }
    expectTable(group + "/set_reactions", setForces);
    EXPECT_EQ(readRawStringAttribute(file_, group + "/set_reactions", "names"), setNames);
    for (const ContactPairRecord& pair : expected.record.contact) {
      const std::string path = group + "/contact/" + pair.name;
      expectTable(path + "/position", pair.position);
      expectVector(path + "/gap", pair.gap);
      expectVector(path + "/normal_traction", pair.normalTraction);
      expectTable(path + "/tangential_traction", pair.tangentialTraction);
      expectVector(path + "/state", pair.state);
      expectVector(path + "/slip_increment", pair.slipIncrement);
      expectVector(path + "/accumulated_slip", pair.accumulatedSlip);
      expectVector(path + "/weight", pair.weight);
      expectVector(path + "/edge_share", pair.edgeShare);
      expectVector(path + "/total_force", pair.totalForce);
      EXPECT_EQ(readRawInts(file_, path + "/slave_nodes"), pair.slaveNodes);
      expectTable(path + "/slave_nodal_force", pair.slaveNodalForce);
    }
  }
  EXPECT_EQ(readRaw(file_, "/steps/000001/contact/pair2/gap").dims, std::vector<hsize_t>{0});
}

TEST_F(RoundTrip, ConvergenceAndCutbackTablesGrowRowByRow) {
  struct Row {
    int step, attempt, iteration;
    double time, residual, relativeResidual, energy, relativeEnergy, wallSeconds;
  };
  // An independent memory type with the documented field names: a renamed field would not read.
  const hid_t type = H5Tcreate(H5T_COMPOUND, sizeof(Row));
  H5Tinsert(type, "step", HOFFSET(Row, step), H5T_NATIVE_INT);
  H5Tinsert(type, "attempt", HOFFSET(Row, attempt), H5T_NATIVE_INT);
  H5Tinsert(type, "iteration", HOFFSET(Row, iteration), H5T_NATIVE_INT);
  H5Tinsert(type, "time", HOFFSET(Row, time), H5T_NATIVE_DOUBLE);
  H5Tinsert(type, "residual", HOFFSET(Row, residual), H5T_NATIVE_DOUBLE);
  H5Tinsert(type, "relative_residual", HOFFSET(Row, relativeResidual), H5T_NATIVE_DOUBLE);
  H5Tinsert(type, "energy", HOFFSET(Row, energy), H5T_NATIVE_DOUBLE);
  H5Tinsert(type, "relative_energy", HOFFSET(Row, relativeEnergy), H5T_NATIVE_DOUBLE);
  H5Tinsert(type, "wall_seconds", HOFFSET(Row, wallSeconds), H5T_NATIVE_DOUBLE);
  const hid_t table = H5Dopen2(file_, "/convergence", H5P_DEFAULT);
  const hid_t space = H5Dget_space(table);
  std::vector<Row> rows(static_cast<size_t>(H5Sget_simple_extent_npoints(space)));
  ASSERT_GE(H5Dread(table, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows.data()), 0);
  H5Sclose(space);
  H5Dclose(table);
  H5Tclose(type);
  ASSERT_EQ(rows.size(), run_->iterations.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    const IterationRecord& expected = run_->iterations[i];
    EXPECT_EQ(rows[i].step, expected.step);
    EXPECT_EQ(rows[i].attempt, expected.attempt);
    EXPECT_EQ(rows[i].iteration, expected.iteration);
    EXPECT_EQ(rows[i].residual, expected.residualNorm);
    EXPECT_EQ(rows[i].relativeEnergy, expected.relativeEnergy);
    EXPECT_EQ(rows[i].wallSeconds, expected.wallSeconds);
  }
  const hid_t cutbacks = H5Dopen2(file_, "/cutbacks", H5P_DEFAULT);
  const hid_t cutbackSpace = H5Dget_space(cutbacks);
  EXPECT_EQ(H5Sget_simple_extent_npoints(cutbackSpace),
            static_cast<hssize_t>(run_->cutbacks.size()));
  H5Sclose(cutbackSpace);
  H5Dclose(cutbacks);
  EXPECT_EQ(readRawStringAttribute(file_, "/summary", "outcome").at(0), "completed");
  EXPECT_EQ(readRawNumberAttribute(file_, "/summary", "total_iterations"),
            static_cast<double>(run_->iterations.size()));
  EXPECT_EQ(readRawNumberAttribute(file_, "/summary", "wall_seconds"), 1.25);
}

TEST_F(RoundTrip, CsvHasOneRowPerStepWithExactValues) {
  std::ifstream csv(run_->csvPath);
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "step,time,iterations,bottom_Fx,bottom_Fy,bottom_Fz,top_Fx,top_Fy,top_Fz,"
            "\"cap, all_Fx\",\"cap, all_Fy\",\"cap, all_Fz\",contact_pair1_Fx,contact_pair1_Fy,"
            "contact_pair1_Fz,contact_pair2_Fx,contact_pair2_Fy,contact_pair2_Fz");
  for (int step = 1; step <= kRoundTripSteps; ++step) {
    SyntheticStep expected;
    roundTripStep(step, expected);
    std::string line;
    ASSERT_TRUE(std::getline(csv, line)) << "missing row of step " << step;
    std::vector<double> values;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) values.push_back(std::stod(cell));
    ASSERT_EQ(values.size(), 18u);
    EXPECT_EQ(values[0], step);
    EXPECT_EQ(values[1], expected.record.time);
    EXPECT_EQ(values[2], expected.record.iterations);
    EXPECT_EQ(values[3 + 3 + 2], expected.record.setReactions[1].second.z());  // top_Fz
    EXPECT_EQ(values[12 + 1], expected.record.contact[0].totalForce.y());      // pair1 Fy
    EXPECT_EQ(values[15 + 2], expected.record.contact[1].totalForce.z());      // pair2 Fz
  }
  std::string extra;
  EXPECT_FALSE(std::getline(csv, extra)) << "unexpected row: " << extra;
}

TEST_F(RoundTrip, XdmfListsEveryStepAndSkipsEmptyPointClouds) {
  std::ifstream xdmf(run_->xdmfPath);
  const std::string text((std::istreambuf_iterator<char>(xdmf)), std::istreambuf_iterator<char>());
  const auto count = [&](const std::string& needle) {
    size_t found = 0;
    for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
      ++found;
    return found;
  };
  EXPECT_EQ(count("<Time Value="), static_cast<size_t>(kRoundTripSteps));
  EXPECT_EQ(count("Name=\"contact pair1\""), static_cast<size_t>(kRoundTripSteps));
  EXPECT_EQ(count("Name=\"contact pair2\""), static_cast<size_t>(kRoundTripSteps - 1));
  EXPECT_EQ(count("TopologyType=\"Hexahedron_27\""), static_cast<size_t>(kRoundTripSteps));
  EXPECT_TRUE(text.ends_with("</Domain>\n</Xdmf>\n"));
}

}  // namespace
}  // namespace cc::test
