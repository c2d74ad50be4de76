// The /cutbacks reason column (format version 2: a fixed-length UTF-8 string, because parallel
// HDF5 cannot write variable-length data): long reasons are cut at a character boundary, reasons
// read back exactly, and version-1 files (variable-length reason) are still read.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "output/results_layout.hpp"
#include "output/results_reader.hpp"
#include "roundtrip_fixture.hpp"

namespace cc::test {
namespace {

TEST(CutbackReason, ShortReasonIsStoredWhole) {
  const layout::CutbackRow row = layout::cutbackRow(3, 0.5, 0.25, "det J < 0 at élément 7");
  EXPECT_STREQ(row.reason, "det J < 0 at élément 7");
  EXPECT_EQ(row.step, 3);
  EXPECT_EQ(row.newDt, 0.25);
}

TEST(CutbackReason, LongReasonIsCutAtACharacterBoundary) {
  // "é" is two bytes: an odd cut would leave half a character.
  std::string reason = "x";
  while (reason.size() < 3 * layout::kReasonBytes) reason += "é";
  const layout::CutbackRow row = layout::cutbackRow(1, 1, 1, reason);
  const std::string stored(row.reason);
  ASSERT_LT(stored.size(), layout::kReasonBytes);
  ASSERT_GE(stored.size(), layout::kReasonBytes - 5);
  ASSERT_EQ(stored.substr(stored.size() - 3), "...");
  const std::string kept = stored.substr(0, stored.size() - 3);
  EXPECT_EQ(reason.compare(0, kept.size(), kept), 0);
  EXPECT_EQ((kept.size() - 1) % 2, 0u) << "cut inside a two-byte character";
}

TEST(CutbackReason, ReasonsReadBackThroughTheReader) {
  const RoundTripRun& run = roundTripRun();
  const std::vector<CutbackRecord> read = ResultsReader(run.h5Path).cutbacks();
  ASSERT_EQ(read.size(), run.cutbacks.size());
  ASSERT_FALSE(read.empty());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].step, run.cutbacks[i].step);
    EXPECT_EQ(read[i].newDt, run.cutbacks[i].newDt);
    EXPECT_EQ(read[i].reason, run.cutbacks[i].reason);
  }
}

TEST(CutbackReason, VersionOneFilesAreStillRead) {
  // A copy of the round-trip file whose /cutbacks is rewritten as format version 1 stored it.
  const RoundTripRun& run = roundTripRun();
  const std::string path = run.directory + "/version1_cutbacks.h5";
  std::filesystem::copy_file(run.h5Path, path, std::filesystem::copy_options::overwrite_existing);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  ASSERT_GE(H5Ldelete(file, layout::kCutbacks, H5P_DEFAULT), 0);
  const hid_t text = H5Tcopy(H5T_C_S1);
  H5Tset_size(text, H5T_VARIABLE);
  const hid_t type = H5Tcreate(H5T_COMPOUND, sizeof(layout::CutbackRowV1));
  H5Tinsert(type, "step", HOFFSET(layout::CutbackRowV1, step), H5T_NATIVE_INT);
  H5Tinsert(type, "time", HOFFSET(layout::CutbackRowV1, time), H5T_NATIVE_DOUBLE);
  H5Tinsert(type, "new_dt", HOFFSET(layout::CutbackRowV1, newDt), H5T_NATIVE_DOUBLE);
  H5Tinsert(type, "reason", HOFFSET(layout::CutbackRowV1, reason), text);
  const layout::CutbackRowV1 rows[2] = {{4, 0.4, 0.05, "first reason"}, {9, 0.9, 0.01, "zweite"}};
  const hsize_t count = 2;
  const hid_t space = H5Screate_simple(1, &count, nullptr);
  const hid_t table =
      H5Dcreate2(file, layout::kCutbacks, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(H5Dwrite(table, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows), 0);
  H5Dclose(table);
  H5Sclose(space);
  H5Tclose(type);
  H5Tclose(text);
  H5Fclose(file);
  const std::vector<CutbackRecord> read = ResultsReader(path).cutbacks();
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].step, 4);
  EXPECT_EQ(read[0].reason, "first reason");
  EXPECT_EQ(read[1].newDt, 0.01);
  EXPECT_EQ(read[1].reason, "zweite");
}

}  // namespace
}  // namespace cc::test
