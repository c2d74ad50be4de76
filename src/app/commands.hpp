// The subcommands of `covcontact`: run a deck, check a deck, compare two results files. Each
// returns the process exit code (ExitCode in common/errors.hpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace cc::app {

struct RunOptions {
  std::string deck;
  std::string output;  // -o; empty = the deck's `output file=` or <deck stem>.h5
  int threads = 0;     // 0 = OpenMP default
  std::string commandLine;
  bool quiet = false;
  std::string restartFile;               // --restart: continue from a step of this results file
  int restartStep = -1;                  // --from-step; -1 = the last step with restart data
  std::vector<std::string> dumpTangent;  // --dump-tangent STEP:ITER[:ATTEMPT] (repeatable)
  std::string dumpDirectory;             // --dump-dir; empty = beside the results file
  bool newtonLog = false;                // --newton-log: one line per Newton iteration
  std::string checkTangent;              // --check-tangent STEP:ITERATION (diagnostics)
  std::string solver;                    // --solver: overrides the deck's solve solver=
  bool cost = false;                     // --cost: print where the time went (JSON)
};

struct SolveDumpOptions {
  std::string directory;
  std::string solver = "auto";
  double rtol = 1e-8;
};
int solveDumpCommand(const SolveDumpOptions& options);

struct CompareOptionsCli {
  std::string run;
  std::string reference;
  double rtol = 1e-8;
  std::optional<double> atol;
  std::vector<std::string> fields;
};

int runCommand(const RunOptions& options);
int checkCommand(const std::string& deck, bool listKeywords);
int compareCommand(const CompareOptionsCli& options);

// --dump-tangent's STEP:ITER[:ATTEMPT] (STEP, ITER >= 1, ATTEMPT >= 0, default 0); nullopt
// when malformed. The command line's validator and the run read it the same way.
struct TangentDumpSelection {
  int step = 0;
  int iteration = 0;
  int attempt = 0;
};
std::optional<TangentDumpSelection> parseTangentDumpSelection(const std::string& text);
// What a malformed selection is told it should be.
inline constexpr const char* kTangentDumpForm =
    "STEP:ITER or STEP:ITER:ATTEMPT (STEP and ITER >= 1, ATTEMPT >= 0)";

// The results path a run writes: -o, else the deck's `output file=`, else <deck stem>.h5 in
// the working directory.
std::string resultsPath(const std::string& deckPath, const std::string& deckOutput,
                        const std::string& commandLineOutput);

}  // namespace cc::app
