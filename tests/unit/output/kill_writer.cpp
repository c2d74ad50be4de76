// Test program for the SIGKILL test (check_kill.py): writes synthetic steps in a loop and prints
// "step <k>" once step k has been written and flushed.
// Usage: kill_writer OUTPUT.h5 MAX_STEPS paced|continuous
//   paced: before writing each step, appends that step's Newton iteration rows a few ms apart and
//          then waits for a line on stdin, like a run that is still solving; the driver decides
//          when a step may be written, so its kill always lands outside writeStep.
//   continuous: writes steps back to back (to measure kills that land inside writeStep).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "synthetic_run.hpp"

namespace {

constexpr std::chrono::milliseconds kIterationPause(5);  // a (very fast) Newton iteration

bool waitForGo() {
  char line[16];
  return std::fgets(line, sizeof line, stdin) != nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4 ||
      (std::strcmp(argv[3], "paced") != 0 && std::strcmp(argv[3], "continuous") != 0)) {
    std::fprintf(stderr, "usage: %s OUTPUT.h5 MAX_STEPS paced|continuous\n", argv[0]);
    return 1;
  }
  const std::string path = argv[1];
  const int maxSteps = std::atoi(argv[2]);
  const bool paced = std::strcmp(argv[3], "paced") == 0;
  const cc::test::SyntheticMesh mesh = cc::test::makeSyntheticMesh();
  cc::ResultsWriter writer;
  writer.open(path, cc::test::syntheticRunInfo(), mesh.mesh);
  for (int step = 1; step <= maxSteps; ++step) {
    cc::test::SyntheticStep data;
    cc::test::fillIntegerStep(mesh.mesh, step, data);
    for (int iteration = 1; iteration <= data.record.iterations; ++iteration) {
      if (paced) std::this_thread::sleep_for(kIterationPause);
      writer.appendIteration(cc::test::syntheticIteration(step, 0, iteration));
    }
    if (paced && !waitForGo()) return 0;
    writer.writeStep(data.record);
    std::printf("step %d\n", step);
    std::fflush(stdout);
  }
  writer.close({"completed", maxSteps, 0, 0, 0, ""});
  return 0;
}
