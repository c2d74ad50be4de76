// ResultsWriter: one HDF5 file per run (deck, mesh, one group per written step, convergence and
// cut-back tables, summary) plus the XDMF and reactions-CSV sidecars (docs/output-format.md).
// Every step is flushed, so a run killed while solving keeps all finished steps readable; a kill
// inside writeStep's own flush can damage the file (HDF5 cannot flush atomically; measured there).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "mesh/mesh.hpp"
#include "output/hdf5_io.hpp"
#include "output/results_file_guard.hpp"
#include "records/output_selection.hpp"
#include "records/result_records.hpp"

namespace cc {

// Where the results came from; stored as attributes of the file's root group.
struct RunInfo {
  std::string deckText;
  std::string commandLine;
  std::string title;
  std::string version;
  std::string deckPath;
  std::vector<std::string> inputFiles;  // never overwritten (checkOutputWritable)
};

// How the run ended; stored as attributes of /summary by close().
struct RunTotals {
  std::string outcome;  // e.g. "completed", "diverged", "interrupted"
  int steps = 0;
  int totalIterations = 0;
  int cutbacks = 0;
  double wallSeconds = 0;
  std::string message;
  // The linear solver: what `solver=` resolved to, Krylov iterations over the run and the
  // Krylov solves redone with a direct solver (0 for direct solvers).
  std::string linearSolver{};
  long krylovIterations = 0;
  int krylovFallbacks = 0;
  int lineSearchRetries = 0;    // failed plain-Newton attempts retried with line search
  int discardedIterations = 0;  // iterations of failed attempts (not in totalIterations)
  int continuationRetries = 0;  // steps retried by penalty continuation after line search
  int stabilizedRetries = 0;    // steps retried with viscous stabilisation (stabilize_on_failure)
  // Lines the run ends with about results to distrust (a penalty too soft for the mesh), one
  // per line; empty: none.
  std::string warnings{};
};

// <dir>/<stem>.xdmf and <dir>/<stem>_reactions.csv beside <dir>/<stem>.h5.
std::string xdmfPathFor(const std::string& h5Path);
std::string csvPathFor(const std::string& h5Path);

// Throws OutputError naming the path if the results file or a selected sidecar cannot be created
// or must not be overwritten: a sidecar that would be the results file itself (`-o run.xdmf`),
// a path that is one of `inputs` (deck, included files, mesh, restart file), or an existing
// file that CovContact did not write (checkReplaceable). Cheap and side-effect free, so the app
// can call it before meshing and solving.
void checkOutputWritable(const std::string& h5Path, const OutputSelection& selection = {},
                         const std::vector<std::string>& inputs = {});

// A run on several processes writes one file collectively (parallel HDF5 over MPI-IO): every
// process calls the writer with the same records, the file's metadata is written by all, the
// rows of every array are divided among the processes (WriteShare), and rank 0 alone checks and
// locks the path and writes the XDMF and CSV sidecars. The output module does not know MPI: the
// process group sets up the property lists (`collective`) and agrees on errors (`agree`).
struct ParallelOutput {
  int rank = 0;
  int size = 1;
  // Makes a file access list use MPI-IO on the run's processes and a transfer list collective.
  std::function<void(hid_t fileAccess, hid_t transfer)> collective;
  // {code, message} of the lowest rank whose code is not 0, on every rank.
  std::function<std::pair<int, std::string>(int, const std::string&)> agree;
};

class ResultsWriter {
 public:
  ResultsWriter();
  ~ResultsWriter();  // closes without a /summary if close() was not called; never throws
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  // Takes the results file's lock (refusing a file another run is writing), checks it may be
  // replaced, then creates (truncates) the files and writes the run info and the mesh. The lock
  // is held until close(). Throws OutputError.
  // With `parallel.size` > 1 every process of the run calls open (and then every other member)
  // together.
  void open(const std::string& path, const RunInfo& info, const Mesh& mesh,
            const OutputSelection& selection = {}, const ParallelOutput& parallel = {});
  // Writes /steps/<6-digit step>, flushes the file, then appends the step to the sidecars.
  // Throws std::invalid_argument if a selected field is missing or has the wrong size.
  void writeStep(const StepRecord& step);
  void appendIteration(const IterationRecord& iteration);
  void appendCutback(const CutbackRecord& cutback);
  // Writes /summary and closes every file; the writer can then be opened again.
  void close(const RunTotals& totals);

  bool isOpen() const;
  const std::string& path() const;

 private:
  struct State;
  void writeStepGroup(const StepRecord& step, hid_t group);
  void writeContact(const StepRecord& step, hid_t stepGroup);
  static void writeEnergy(h5::FileRef file, hid_t stepGroup, const EnergyRecord& energy);
  std::unique_ptr<State> state_;
};

}  // namespace cc
