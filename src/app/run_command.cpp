// `covcontact run`: deck -> model -> load stepping -> results file, with progress, signal
// handling (SIGINT/SIGTERM stop after the current iteration or Krylov iteration) and a closing
// summary. Under `mpirun -np N` every process runs this same flow on the whole model (model/
// model_distribution.cpp divides the work); all of them write the one results file together
// (parallel HDF5, ResultsWriter's ParallelOutput), rank 0 alone prints, errors are agreed on
// (ProcessGroup::agree) and reported once, and a process that must stop alone ends the whole run
// (ProcessGroup::abort) rather than leave the others waiting.
#include <fmt/format.h>
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <new>
#include <numbers>
#include <sstream>

#include "app/allocation_failure.hpp"
#include "app/commands.hpp"
#include "app/heap_policy.hpp"
#include "app/progress.hpp"
#include "app/restart.hpp"
#include "app/stop_signals.hpp"
#include "common/errors.hpp"
#include "deck/deck_parser.hpp"
#include "deck/spec_choices.hpp"
#include "model/model.hpp"
#include "output/hdf5_io.hpp"
#include "output/results_file_guard.hpp"
#include "output/results_writer.hpp"
#include "parallel/process_group.hpp"
#include "solver/load_stepper.hpp"
#include "verification/reference_report.hpp"
#include "verification/reference_tracker.hpp"

namespace cc::app {

namespace {

// What did not fit when memory ran out, with the model's size, the size asked for, the memory
// the process had reached and its limit (std::bad_alloc itself says none of these).
std::string outOfMemoryMessage(const char* during, const Model* model) {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  std::string text = fmt::format("out of memory while {}", during);
  if (model)
    text += fmt::format(" ({} nodes, {} elements, {} equations)", model->mesh().numNodes(),
                        model->elementCount(), model->dofMap().numFree());
  return text + failedAllocationText() + "; the resident memory of the process had reached " +
         byteSize(static_cast<double>(usage.ru_maxrss) * 1024) + addressSpaceLimitText() +
         "; use fewer elements or a machine with more memory";
}

// Receives the stepper's records: writes them and reports progress.
class RunObserver : public StepObserver {
 public:
  // Under mpirun every process writes its share of the one results file (with the same
  // records), and rank 0 alone (`reports`) prints progress.
  RunObserver(Model& model, ResultsWriter& writer, bool reports, Progress& progress,
              bool withStress, ProcessGroup& group,
              verification::ReferenceTracker* references = nullptr)
      : model_(model),
        writer_(writer),
        reports_(reports),
        progress_(progress),
        withStress_(withStress),
        group_(group),
        references_(references) {}

  void iteration(const IterationRecord& record) override {
    writer_.appendIteration(record);
    if (reports_) progress_.iteration(record);
  }
  void cutback(const CutbackRecord& record) override {
    writer_.appendCutback(record);
    if (reports_) progress_.cutback(record);
  }
  void note(const std::string& line) override {
    if (line.rfind("linear solver: ", 0) == 0) linearSolver_ = line.substr(15);
    if (reports_) progress_.note(line);
  }
  const std::string& linearSolver() const { return linearSolver_; }
  // The stepper whose next step size the restart data of every written step records.
  void attach(const LoadStepper& stepper) { stepper_ = &stepper; }

  void convergedResidual(double relative) override {
    if (reports_) progress_.convergedResidual(relative);
  }
  void stepConverged(int step, double time, int iterations, int cutbacks,
                     const Eigen::VectorXd& displacement, const Eigen::VectorXd& internalForce,
                     bool writeOutput) override {
    // The state is the same on every process: each computes the same record.
    model_.accountEnergy(time, displacement, internalForce);  // every step: a running sum
    const bool compare = references_ && !references_->empty();
    if (writeOutput || compare) {
      StepRecord record = model_.stepRecord(step, time, iterations, cutbacks, displacement,
                                            internalForce, withStress_ && writeOutput);
      if (writeOutput) {
        const RestartRecord restart =
            restartRecordOf(model_, displacement, stepper_->nextStepSize(), *stepper_);
        record.restart = &restart;
        writer_.writeStep(record);
        ++writtenSteps_;
      }
      if (compare) references_->observe(record);  // every converged step, written or not
    }
    if (reports_) {
      const EnergyRecord& energy = model_.energy();
      const double share = energy.stabilizationDissipation > 0 && energy.externalWork != 0
                               ? energy.stabilizationDissipation / std::abs(energy.externalWork)
                               : 0.0;
      progress_.stepConverged(step, time, iterations, cutbacks, share);
    }
  }
  // Several processes: a signal may reach them at different iterations; all stop at the first
  // poll after any one of them got it.
  bool stopRequested() const override { return group_.maximum(app::stopRequested() ? 1 : 0) != 0; }
  int writtenSteps() const { return writtenSteps_; }

 private:
  Model& model_;
  ResultsWriter& writer_;
  bool reports_;
  Progress& progress_;
  bool withStress_;
  ProcessGroup& group_;
  verification::ReferenceTracker* references_;
  const LoadStepper* stepper_ = nullptr;
  std::string linearSolver_;
  int writtenSteps_ = 0;
};

// Where the converged steps are, truthfully when output_every left some of them out.
std::string keptStepsMessage(int converged, int written, const std::string& path) {
  if (written == converged)
    return fmt::format("covcontact: the {} converged steps are kept in {}\n", converged, path);
  return fmt::format(
      "covcontact: {} of the {} converged steps are written in {} (output_every "
      "writes only some steps)\n",
      written, converged, path);
}

const char* outcomeName(RunSummary::Outcome outcome) {
  switch (outcome) {
    case RunSummary::Outcome::Completed:
      return "completed";
    case RunSummary::Outcome::Diverged:
      return "diverged";
    case RunSummary::Outcome::Interrupted:
      return "interrupted";
    case RunSummary::Outcome::Singular:
      return "singular";
  }
  return "?";
}

int exitCodeOf(RunSummary::Outcome outcome) {
  switch (outcome) {
    case RunSummary::Outcome::Completed:
      return kExitOk;
    case RunSummary::Outcome::Diverged:
      return kExitDiverged;
    case RunSummary::Outcome::Interrupted:
      return kExitInterrupted;
    case RunSummary::Outcome::Singular:
      return kExitSingular;
  }
  return kExitInternal;
}

// Where each dump goes: <dir>/<results stem>_tangent_STEP_ITER (a later attempt: _aATTEMPT
// appended), <dir> = --dump-dir or the results file's directory.
TangentDumpRequest dumpRequest(const std::string& text, const std::filesystem::path& directory,
                               const std::string& resultsStem) {
  const std::optional<TangentDumpSelection> selection = parseTangentDumpSelection(text);
  if (!selection) {
    throw std::invalid_argument(std::string("--dump-tangent expects ") + kTangentDumpForm +
                                ", got '" + text + "'");
  }
  TangentDumpRequest request;
  request.step = selection->step;
  request.iteration = selection->iteration;
  request.attempt = selection->attempt;
  std::string name = fmt::format("{}_tangent_{}_{}", resultsStem, request.step, request.iteration);
  if (request.attempt > 0) name += fmt::format("_a{}", request.attempt);
  request.directory = (directory / name).string();
  return request;
}

double endTime(const ProblemSpec& spec) {
  double time = 0;
  for (const PhaseSpec& phase : spec.phases) time += phase.steps * phase.dt;
  return time;
}

}  // namespace

std::optional<TangentDumpSelection> parseTangentDumpSelection(const std::string& text) {
  TangentDumpSelection selection;
  char colon = 0;
  std::istringstream in(text);
  if (!(in >> selection.step >> colon >> selection.iteration) || colon != ':') return std::nullopt;
  if (!in.eof() && !(in >> colon >> selection.attempt && colon == ':')) return std::nullopt;
  if (!in.eof() || selection.step < 1 || selection.iteration < 1 || selection.attempt < 0) {
    return std::nullopt;
  }
  return selection;
}

std::string resultsPath(const std::string& deckPath, const std::string& deckOutput,
                        const std::string& commandLineOutput) {
  if (!commandLineOutput.empty()) return commandLineOutput;
  if (!deckOutput.empty()) return deckOutput;
  return std::filesystem::path(deckPath).stem().string() + ".h5";
}

namespace {

// What stops a run before its first step: the exit code and the message (printed once).
struct SetupError {
  int code = kExitOk;
  std::string message;
};

// What a run is built from: the model on every process, the deck's reference values, where the
// results go, where the run starts, and the files it must never replace.
struct PreparedRun {
  std::unique_ptr<Model> model;
  std::unique_ptr<verification::ReferenceTracker> references;
  std::string path;
  OutputSelection selection;
  StartState startState;
  std::vector<std::string> inputs;
  std::string partition;  // how the model was divided between processes (empty on one)
};

// Reads the deck, checks the results path and builds the model (on every process). Errors are
// returned, not printed: under mpirun the processes first agree on them.
SetupError setUp(const RunOptions& options, bool writes, PreparedRun& run) {
  try {
    const ProblemSpec spec = parseDeck(options.deck);
    run.path = resultsPath(options.deck, spec.output.file, options.output);
    run.selection = outputSelection(spec.output);
    if (!options.restartFile.empty() && sameFile(run.path, options.restartFile)) {
      return {kExitUsage, "covcontact: error: the results file '" + run.path +
                              "' is the restart file; give another one with -o"};
    }
    run.inputs = spec.deckFiles;
    run.inputs.push_back(spec.mesh.path);
    if (!options.restartFile.empty()) run.inputs.push_back(options.restartFile);
    if (writes) checkOutputWritable(run.path, run.selection, run.inputs);
    run.model = buildModel(spec);
    run.references = std::make_unique<verification::ReferenceTracker>(*run.model);
    if (!options.restartFile.empty())
      run.startState = restartFrom(options.restartFile, options.restartStep, *run.model);
  } catch (const InputError& error) {
    return {kExitInput, error.what()};
  } catch (const OutputError& error) {
    return {kExitIo, std::string("covcontact: error: ") + error.what()};
  } catch (const OutOfMemory& error) {
    return {kExitOutOfMemory,
            std::string("covcontact: error: ") + error.what() + addressSpaceLimitText()};
  } catch (const std::bad_alloc&) {
    return {kExitOutOfMemory,
            "covcontact: error: " +
                outOfMemoryMessage("reading the mesh and building the model", run.model.get())};
  }
  return {};
}

// `--cost`: where the time of every process went and what moved between them, one JSON line
// (scripts/bench_mpi.py reads it). Collective: every process calls it.
std::string costLine(const Model& model, const SolverStatistics& work, int iterations,
                     double wallSeconds, ProcessGroup& group) {
  constexpr int kFields = 8;
  const AssemblyTimings& timings = model.assemblyTimings();
  const std::size_t elementSets = model.elementSets().size();
  double elements = 0, contact = timings.prepare;  // prepare = contact search and projection
  for (std::size_t c = 0; c < timings.byContribution.size(); ++c) {
    (c < elementSets ? elements : contact) += timings.byContribution[c].evaluate;
  }
  contact += model.contactCompletionSeconds();  // the others' points, once per converged solve
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  const double cpu = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                     1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  const LinearSolverStatistics& linear = work.linear;
  const double mine[kFields] = {
      cpu,
      static_cast<double>(usage.ru_maxrss) / 1024.0,
      elements,
      contact,
      linear.analysisSeconds + linear.factorizationSeconds + linear.solveSeconds,
      linear.matrixBytesSent,
      linear.solutionBytesReceived,
      timings.pattern};
  const int processes = group.size();
  std::vector<double> all(static_cast<std::size_t>(kFields * processes), 0.0);
  std::copy(mine, mine + kFields, all.begin() + kFields * group.rank());
  group.sum(all.data(), all.size());
  auto column = [&](int field) {
    std::string text = "[";
    for (int p = 0; p < processes; ++p) {
      text += fmt::format("{}{:.6g}", p ? ", " : "",
                          all[static_cast<std::size_t>(kFields * p + field)]);
    }
    return text + "]";
  };
  auto total = [&](int field) {
    double sum = 0;
    for (int p = 0; p < processes; ++p) sum += all[static_cast<std::size_t>(kFields * p + field)];
    return sum;
  };
  const double perIteration = iterations > 0 ? 1.0 / iterations : 0.0;
  return fmt::format(
      "cost: {{\"processes\": {}, \"equations\": {}, \"elements\": {}, \"assemblies\": {}, "
      "\"iterations\": {}, \"wall_s\": {:.6g}, "
      "\"cpu_s\": {}, \"peak_rss_mib\": {}, \"elements_s\": {}, \"contact_s\": {}, "
      "\"linear_solve_s\": {}, \"pattern_s\": {}, "
      "\"bytes_per_iteration\": {{\"force_sums\": {:.6g}, "
      "\"matrix_entries\": {:.6g}, \"solution\": {:.6g}}}, \"linear_phases_rank0\": "
      "{{\"analyses\": {}, \"analysis_s\": {:.6g}, \"factorizations\": {}, "
      "\"factorization_s\": {:.6g}, \"reused_preconditioners\": {}, \"solves\": {}, "
      "\"solve_s\": {:.6g}, \"krylov_iterations\": {}, \"refinement_steps\": {}}}}}\n",
      processes, model.dofMap().numFree(), model.elementCount(), timings.assemblies, iterations,
      wallSeconds, column(0), column(1), column(2), column(3), column(4), column(7),
      group.bytesMoved() * perIteration, total(5) * perIteration, total(6) * perIteration,
      linear.analyses, linear.analysisSeconds, linear.factorizations, linear.factorizationSeconds,
      linear.reusedPreconditioners, linear.solves, linear.solveSeconds, linear.krylovIterations,
      linear.refinementSteps);
}

// Rank 0's value on every process: what the processes write into the shared file must be the
// same everywhere (a wall time measured on each differs).
double rankZeroValue(ProcessGroup& group, double value) {
  if (group.rank() != 0) value = 0;
  group.sum(&value, 1);
  return value;
}

// Options that inspect one process's whole tangent, which no process has under mpirun.
SetupError refuseSerialOnlyOptions(const RunOptions& options, const ProcessGroup& group) {
  if (group.size() == 1) return {};
  for (const auto& [given, name] : {std::pair{!options.dumpTangent.empty(), "--dump-tangent"},
                                    std::pair{!options.checkTangent.empty(), "--check-tangent"}}) {
    if (given) {
      return {kExitUsage, fmt::format("covcontact: error: {} needs the whole tangent in one "
                                      "process; run it without mpirun (or with -np 1)",
                                      name)};
    }
  }
  return {};
}

// Notes on each contact pair before the first step, so that a user sees what the run chose for
// them and where their model costs accuracy or Newton iterations.
void printContactPairNotes(const Model& model) {
  for (const auto& pair : model.contactPairs()) {
    const contact::ContactPairConfig& config = pair->config();
    if (config.automaticPenalty) {
      printOut(fmt::format("contact '{}': automatic penalty eps_n = {:.6g}, eps_t = {:.6g}\n",
                           config.name, config.law.penaltyNormal, config.law.penaltyTangential));
    }
    // What the smoothing keeps sharp, so that a user sees a tool's edges were recognised (or
    // that crease= should be higher for a coarse curved mesh whose facets turn by more).
    if (config.smoothMaster && pair->creaseCount() > 0) {
      printOut(
          fmt::format("contact '{}': surface=smooth keeps {} edge{} sharp (facets meeting "
                      "at more than crease = {:g} degrees)\n",
                      config.name, pair->creaseCount(), pair->creaseCount() == 1 ? "" : "s",
                      config.creaseAngle * 180 / std::numbers::pi));
    }
    // A searched master meshed as facets of a curved surface: points crossing its facet edges
    // make the residual jump, which costs Newton iterations in sliding and makes the force
    // jitter (issue 14: 6.2 against 3.2 iterations per step on the ironing die); the smoothing
    // is the remedy, so name it.
    if (!config.smoothMaster && config.kind != contact::PointKind::SegmentToAnalytical) {
      const auto turns = pair->facetTurns(model.mesh().coordinates);
      if (turns.sharedEdges > 0 && 4 * turns.turning >= turns.sharedEdges) {
        printOut(fmt::format(
            "contact '{}': the master is a curved surface meshed as facets ({} of {} shared "
            "edges turn by more than 1 degree, up to {:.2g}); points crossing facet edges cost "
            "Newton iterations in sliding, surface=smooth models the surface smoothly "
            "(docs/verification/smooth_master.md)\n",
            config.name, turns.turning, turns.sharedEdges, turns.largest * 180 / std::numbers::pi));
      }
    }
    // A penalty far above E/h makes Newton's region of convergence small: say so, with the value
    // the automatic penalty would take (a step failing there is retried by penalty continuation,
    // solver/load_stepper.cpp).
    const double ratio = pair->penaltyRatio();
    if (!config.automaticPenalty && ratio > 100) {
      printOut(fmt::format(
          "contact '{}': the penalty is {:.3g} times the automatic one ({:.6g}, 10 E/h of the "
          "contact surfaces)\n",
          config.name, ratio, config.referencePenalty));
    }
  }
}

// Solution control the deck chose without saying so, which changes the Newton counts a user
// compares between runs.
void printNewtonNotes(const ProblemSpec& spec) {
  // The line search that an augmented pair turns on (deck/solve_keywords.cpp).
  const bool defaultLineSearch =
      std::any_of(spec.phases.begin(), spec.phases.end(), [](const PhaseSpec& phase) {
        return phase.newton.lineSearch && !phase.newton.lineSearchChosen;
      });
  if (defaultLineSearch) {
    printOut(
        "newton: line search on (an enforcement=augmented contact pair; line_search=no "
        "turns it off)\n");
  }
  const double inner = spec.phases.front().newton.augmentedInnerTolerance;
  if (spec.hasAugmentedContact() && inner > 0) {
    printOut(
        fmt::format("newton: augmented re-solves stop at aug_inner = {:g} of their first "
                    "residual; each step ends with a full solve\n",
                    inner));
  }
}

// The lines before the first step (one process prints them, and none under -q).
void printRunHeader(const RunOptions& options, const Model& model, const std::string& partition,
                    const StartState& startState) {
  const ProblemSpec& spec = model.spec();
  printOut(fmt::format("{}: {} nodes, {} elements, {} equations, {} contact points, {} threads\n",
                       spec.title.empty() ? options.deck : spec.title, model.mesh().numNodes(),
                       model.elementCount(), model.dofMap().numFree(), model.contactPointCount(),
                       model.threads()));
  if (!partition.empty()) printOut(partition + "\n");
  printContactPairNotes(model);
  printNewtonNotes(spec);
  if (!options.restartFile.empty()) {
    printOut(fmt::format("continuing from step {} (t = {:.6g}) of {}\n", startState.step,
                         startState.time, options.restartFile));
  }
}

// Opens the results file, on several processes together (parallel HDF5); the processes agree on
// a failure, which every one of them returns.
SetupError openResults(ResultsWriter& writer, ProcessGroup& group, const RunOptions& options,
                       const Model& model, const std::string& path,
                       const OutputSelection& selection, const std::vector<std::string>& inputs) {
  const ProblemSpec& spec = model.spec();
  SetupError opened;
  ParallelOutput parallel;
  if (group.size() > 1) {
    parallel = {
        group.rank(), group.size(),
        [&group](hid_t access, hid_t transfer) { group.useCollectiveFile(access, transfer); },
        [&group](int code, const std::string& message) { return group.agree(code, message); }};
  }
  try {
    writer.open(
        path,
        {spec.deckText, options.commandLine, spec.title, COVCONTACT_VERSION, options.deck, inputs},
        model.mesh(), selection, parallel);
  } catch (const OutputError& error) {
    opened = {kExitIo, std::string("covcontact: error: ") + error.what()};
  }
  const auto [code, message] = group.agree(opened.code, opened.message);
  return {code, message};
}

// The stepper with the command line's diagnostics and linear-solver choice over the deck's.
std::unique_ptr<LoadStepper> makeStepper(const RunOptions& options, Model& model,
                                         StepObserver& observer, const std::string& path) {
  const ProblemSpec& spec = model.spec();
  std::vector<TangentDumpRequest> dumps;
  const std::filesystem::path results(path);
  const std::filesystem::path dumpDirectory = options.dumpDirectory.empty()
                                                  ? results.parent_path()
                                                  : std::filesystem::path(options.dumpDirectory);
  for (const std::string& text : options.dumpTangent) {
    dumps.push_back(dumpRequest(text, dumpDirectory, results.stem().string()));
  }
  LinearSolverSpec linearSolver = spec.linearSolver;
  if (!options.solver.empty()) {
    linearSolver.method = deck::choiceValue(deck::linearSolverMethods(), options.solver);
  }
  auto stepper = std::make_unique<LoadStepper>(model, observer, spec.phases, linearSolver, dumps);
  if (!options.checkTangent.empty()) {
    int step = 0, iteration = 0;
    std::sscanf(options.checkTangent.c_str(), "%d:%d", &step, &iteration);  // validated by CLI
    stepper->setTangentCheck(step, iteration);
  }
  return stepper;
}

// What /summary records of a run that a step's exception ended (no counts of retries: the run
// did not finish its accounting).
RunTotals stoppedRunTotals(const char* outcome, const SolverStatistics& done, double seconds,
                           const std::string& message, const std::string& linearSolver) {
  return {outcome,
          done.steps,
          done.iterations,
          done.cutbacks,
          seconds,
          message,
          linearSolver,
          done.linear.krylovIterations,
          done.linear.krylovFallbacks};
}

// The line a completed run ends with; the work of failed attempts (retried with line search or
// cut back) is not in the iterations of the converged steps and is said separately.
std::string completedLine(const RunSummary& summary, double seconds, const std::string& path) {
  std::string continued =
      summary.continuationRetries > 0
          ? fmt::format(", {} by penalty continuation", summary.continuationRetries)
          : std::string();
  if (summary.stabilizedRetries > 0) {
    continued += fmt::format(", {} with viscous stabilisation", summary.stabilizedRetries);
  }
  const std::string discarded =
      summary.discardedIterations > 0
          ? fmt::format(" (+{} in failed attempts, {} retried with line search{})",
                        summary.discardedIterations, summary.lineSearchRetries, continued)
          : std::string();
  return fmt::format(
      "completed: {} steps, {} Newton iterations{}, {} cut-backs in {:.2f} s; results in {}\n",
      summary.stepsConverged, summary.totalIterations, discarded, summary.totalCutbacks, seconds,
      path);
}

// The stabilisation's forces are not part of the model: how much of the work they took is what
// tells whether the answer is still the quasi-static one (Abaqus's ALLSD check).
void printStabilizationShare(const EnergyRecord& energy) {
  if (energy.stabilizationDissipation <= 0) return;
  printOut(fmt::format(
      "viscous stabilisation dissipated {:.4g}, {:.3g} % of the work of the "
      "loads, supports and moving rigid surfaces ({:.4g}); the strain energy is {:.4g}\n",
      energy.stabilizationDissipation,
      100 * energy.stabilizationDissipation / std::abs(energy.externalWork), energy.externalWork,
      energy.strainEnergy));
}

// A penalty too soft for the mesh fails nothing, it only gives other answers: said at the end
// and kept in /summary, one line per pair.
std::string penetrationWarnings(const Model& model) {
  std::string warnings;
  for (const auto& pair : model.contactPairs()) {
    if (const std::string warning = pair->penetrationWarning(); !warning.empty()) {
      warnings += warning + "\n";
    }
  }
  return warnings;
}

// The deck's reference values against what the run measured, printed and stored in the results
// file; the exit code of a file that could not take them.
int reportReferenceErrors(const verification::ReferenceTracker& references,
                          const RunSummary& summary, double seconds, const std::string& path) {
  if (references.empty()) return kExitOk;
  const verification::RunCost cost{seconds, summary.totalIterations, summary.stepsConverged};
  const auto errors = references.results();
  printOut(verification::formatReferenceErrors(errors, cost));
  try {
    verification::writeReferenceErrors(path, errors, cost);
  } catch (const OutputError& error) {
    std::cerr << "covcontact: error: " << error.what() << "\n";
    return kExitIo;
  }
  return kExitOk;
}

// Reads the deck and builds and divides the model on every process; the processes agree on a
// failure, which every one of them returns.
SetupError prepareRun(const RunOptions& options, ProcessGroup& group, PreparedRun& run) {
  const bool writes = group.rank() == 0;  // the one process that checks the results path
  SetupError setup = refuseSerialOnlyOptions(options, group);
  if (setup.code == kExitOk) {
    setup = setUp(options, writes, run);
  }
  const auto [code, message] = group.agree(setup.code, setup.message);
  if (code != kExitOk) return {code, message};
  try {
    run.partition = run.model->distribute(group);
  } catch (const InputError& error) {
    // A deck option not available on several processes: every process finds it the same way.
    return {kExitInput, error.what()};
  }
  return {};
}

// What ending a run needs to close its file and say where its converged steps are.
struct RunEnding {
  ProcessGroup& group;
  bool writes;  // the one process that prints
  const std::string& path;
  ResultsWriter& writer;
  Progress& progress;
  const RunObserver& observer;
  const LoadStepper& stepper;
  const Model& model;
};

// A process that has to stop on its own (rank 0's results file failed, memory ran out on one
// process) takes the others with it: they would wait for it in the next collective operation.
int stopAlone(ProcessGroup& group, int code) {
  if (group.size() > 1) group.abort(code);
  return code;
}

// A deck function that fails only when evaluated (an expression that is not finite at some t):
// the converged steps stay in the file, which is closed with the reason. Every process evaluates
// the same functions at the same times, so they all get here.
int endAfterInputError(const InputError& error, const RunEnding& run, double seconds) {
  run.progress.finish();
  const SolverStatistics done = run.stepper.statistics();
  if (run.writes) {
    std::cerr << error.what() << "\n";
    std::cerr << keptStepsMessage(done.steps, run.observer.writtenSteps(), run.path);
  }
  run.writer.close(stoppedRunTotals("input error", done, rankZeroValue(run.group, seconds),
                                    error.what(), run.observer.linearSolver()));
  return kExitInput;
}

// Memory ran out in a step (the factor, an assembly): the converged steps are on disk; the file
// is closed with the reason, which names what did not fit where it is known. Any other
// exception is an internal error: rethrown on one process, ended alone on several. Called from
// a handler only.
int endAfterException(const std::exception& error, const RunEnding& run, double seconds) {
  const bool outOfMemory = dynamic_cast<const OutOfMemory*>(&error) != nullptr ||
                           dynamic_cast<const std::bad_alloc*>(&error) != nullptr;
  if (!outOfMemory) {
    if (run.group.size() == 1) throw;
    std::cerr << "covcontact: internal error on process " << run.group.rank() << ": "
              << error.what() << "\n";
    return stopAlone(run.group, kExitInternal);
  }
  run.progress.finish();
  const SolverStatistics done = run.stepper.statistics();
  const std::string message = dynamic_cast<const OutOfMemory*>(&error)
                                  ? error.what() + addressSpaceLimitText()
                                  : outOfMemoryMessage("solving a step", &run.model);
  std::cerr << "covcontact: error: " << message << "\n";
  std::cerr << keptStepsMessage(done.steps, run.observer.writtenSteps(), run.path);
  // On several processes the file is written together; memory runs out on one process, which
  // ends the run alone (the file keeps every step written so far, each flushed when written).
  if (run.group.size() == 1) {
    run.writer.close(
        stoppedRunTotals("out of memory", done, seconds, message, run.observer.linearSolver()));
  }
  return stopAlone(run.group, kExitOutOfMemory);
}

}  // namespace

// Reads and builds on every process, opens the one results file, steps the load, closes the
// file with the run's totals and says how the run ended. Each phase's failure is agreed on by
// the processes and ends the run with its exit code.
int runCommand(const RunOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto secondsSinceStart = [&start] {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  if (options.threads > 0) omp_set_num_threads(options.threads);
  ProcessGroup& group = processGroup();
  const bool writes = group.rank() == 0;  // the one process that prints
  PreparedRun run;
  if (const SetupError setup = prepareRun(options, group, run); setup.code != kExitOk) {
    if (writes) std::cerr << setup.message << "\n";
    return setup.code;
  }
  Model& model = *run.model;
  const std::string& path = run.path;
  chooseHeapPolicy(static_cast<std::size_t>(model.dofMap().numFree()));
  const bool quiet = options.quiet || !writes;
  if (!quiet) printRunHeader(options, model, run.partition, run.startState);

  ResultsWriter writer;
  if (const SetupError opened =
          openResults(writer, group, options, model, path, run.selection, run.inputs);
      opened.code != kExitOk) {
    if (writes) std::cerr << opened.message << "\n";
    return opened.code;
  }
  Progress progress(endTime(model.spec()), quiet, options.newtonLog && writes, group.size() == 1);
  RunObserver observer(model, writer, writes, progress, run.selection.stress, group,
                       writes ? run.references.get() : nullptr);
  stopAfterIteration();
  const std::unique_ptr<LoadStepper> stepper = makeStepper(options, model, observer, path);
  observer.attach(*stepper);
  const RunEnding ending{group, writes, path, writer, progress, observer, *stepper, model};
  RunSummary summary;
  try {
    summary = stepper->run(run.startState);
  } catch (const OutputError& error) {
    progress.finish();
    std::cerr << "covcontact: error: " << error.what() << "\n";
    return stopAlone(group, kExitIo);
  } catch (const InputError& error) {
    return endAfterInputError(error, ending, secondsSinceStart());
  } catch (const std::exception& error) {
    return endAfterException(error, ending, secondsSinceStart());
  }
  // The handlers stay until the file is closed: a second interrupt arriving while the run winds
  // up must end it through requestStop (exit 4, file intact), not by the default action.
  progress.finish();
  const double seconds = secondsSinceStart();
  const SolverStatistics work = stepper->statistics();
  const std::string cost =
      options.cost ? costLine(model, work, summary.totalIterations + summary.discardedIterations,
                              seconds, group)
                   : std::string();
  const std::string warnings = penetrationWarnings(model);
  writer.close({outcomeName(summary.outcome), summary.stepsConverged, summary.totalIterations,
                summary.totalCutbacks, rankZeroValue(group, seconds), summary.message,
                observer.linearSolver(), work.linear.krylovIterations, work.linear.krylovFallbacks,
                summary.lineSearchRetries, summary.discardedIterations, summary.continuationRetries,
                summary.stabilizedRetries, warnings});
  if (!writes) return exitCodeOf(summary.outcome);
  if (summary.outcome == RunSummary::Outcome::Completed) {
    printOut(completedLine(summary, seconds, path));
  }
  printStabilizationShare(model.energy());
  if (!warnings.empty()) printOut(warnings);
  if (!cost.empty()) printOut(cost);
  if (group.size() > 1 && !options.quiet) {
    printOut(fmt::format(
        "contact points whose master segment moved to another process: {} (summed over steps)\n",
        model.masterOwnerChanges()));
  }
  if (const int code = reportReferenceErrors(*run.references, summary, seconds, path);
      code != kExitOk) {
    return code;
  }
  if (summary.outcome != RunSummary::Outcome::Completed) {
    std::cerr << fmt::format("covcontact: run {} at t = {:.6g}: {}\n", outcomeName(summary.outcome),
                             summary.finalTime, summary.message)
              << keptStepsMessage(summary.stepsConverged, observer.writtenSteps(), path);
  }
  return exitCodeOf(summary.outcome);
}

}  // namespace cc::app
