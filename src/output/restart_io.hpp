// Restart data in the results file: the group /steps/<step>/restart that ResultsWriter adds to
// every written step (displacement unless the step already stores it, element and contact
// history, the load stepper's step size), and reading it back for `covcontact run --restart`.
// Layout: docs/output-format.md, section "Restart data".
#pragma once

#include <string>
#include <vector>

#include "output/hdf5_io.hpp"
#include "records/result_records.hpp"

namespace cc {

namespace layout {
inline constexpr const char* kRestartGroup = "restart";
inline constexpr const char* kElementHistoryGroup = "element_history";
inline constexpr const char* kContactHistoryGroup = "contact_history";
}  // namespace layout

// Writes `restart` into a new group "restart" of `stepGroup`. The displacement is written only
// if `withDisplacement` (otherwise the step's own displacement dataset serves).
void writeRestart(h5::FileRef file, hid_t stepGroup, const RestartRecord& restart,
                  bool withDisplacement);

// A converged step of a results file that a run can continue from.
struct RestartPoint {
  int step = 0;
  double time = 0;
  RestartRecord record;
};

// Steps of `path` that hold restart data, ascending. Throws OutputError if the file is not a
// readable results file.
std::vector<int> restartSteps(const std::string& path);

// Reads step `step` (-1: the last one with restart data). Throws OutputError naming the file if
// it has no restart data for that step or the data is incomplete.
RestartPoint readRestart(const std::string& path, int step = -1);

}  // namespace cc
