// `covcontact compare RUN REFERENCE`: iteration counts exactly, chosen fields within tolerance.
#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <thread>

#include "app/commands.hpp"
#include "app/progress.hpp"
#include "common/errors.hpp"
#include "output/compare.hpp"
#include "output/hdf5_io.hpp"
#include "output/results_file_guard.hpp"

namespace cc::app {

namespace {
constexpr int kReadAttempts = 10;
}  // namespace

int compareCommand(const CompareOptionsCli& cli) {
  CompareOptions options;
  options.rtol = cli.rtol;
  options.atol = cli.atol;
  if (!cli.fields.empty()) options.fields = cli.fields;
  // A file a run is still writing is read between two of its flushes: the reader holds the
  // writer off (ConsistencyLock). A read can still fail if the writer stopped waiting (after a
  // minute of readers) or a writer without that lock (an older version) is at work: it is then
  // retried a few times before giving up with a message that says so.
  const auto inProgress = [&] {
    for (const std::string& path : {cli.run, cli.reference})
      if (beingWritten(path)) return path;
    return std::string();
  };
  for (int attempt = 1;; ++attempt) {
    try {
      const CompareResult result = compareRuns(cli.run, cli.reference, options);
      const std::string writing = inProgress();
      if (!writing.empty())
        printErr(
            fmt::format("covcontact compare: note: '{}' is being written by a run in "
                        "progress; only its finished steps were compared\n",
                        writing));
      printOut(result.report);
      return result.match ? kExitOk : kExitMismatch;
    } catch (const OutputError& error) {
      const std::string writing = inProgress();
      if (!writing.empty() && attempt < kReadAttempts) {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        continue;
      }
      std::cerr << "covcontact compare: error: " << error.what() << "\n";
      if (!writing.empty())
        std::cerr << fmt::format(
            "covcontact compare: '{}' is being written by a run in "
            "progress and could not be read consistently in {} attempts; "
            "compare it when the run has finished\n",
            writing, kReadAttempts);
      return kExitIo;
    }
  }
}

}  // namespace cc::app
