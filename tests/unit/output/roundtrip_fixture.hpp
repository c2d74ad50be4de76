// Shared round-trip run for the output tests: writes a 3-step synthetic run once per test process
// (HDF5, XDMF, CSV) and the expected values as JSON for the h5py and ParaView checks.
#pragma once

#include <hdf5.h>

#include <string>
#include <vector>

#include "synthetic_run.hpp"

namespace cc::test {

inline constexpr int kRoundTripSteps = 3;

struct RoundTripRun {
  std::string directory;  // $COVCONTACT_OUTPUT_TEST_DIR if set (CTest fixture), else a temp dir
  std::string h5Path;
  std::string xdmfPath;
  std::string csvPath;
  std::string jsonPath;
  SyntheticMesh mesh;
  std::vector<IterationRecord> iterations;
  std::vector<CutbackRecord> cutbacks;
  RunTotals totals;
};

// Written on first use; later calls return the same run.
const RoundTripRun& roundTripRun();

// The step records as written (regenerated from the synthetic formulas).
void roundTripStep(int step, SyntheticStep& out);

// Raw HDF5 C API reads, independent of the module's own reader.
struct RawArray {
  std::vector<hsize_t> dims;
  std::vector<double> values;  // row-major
};
RawArray readRaw(hid_t file, const std::string& path);
std::vector<int> readRawInts(hid_t file, const std::string& path);
double readRawNumberAttribute(hid_t file, const std::string& object, const std::string& name);
std::vector<std::string> readRawStringAttribute(hid_t file, const std::string& object,
                                                const std::string& name);

}  // namespace cc::test
