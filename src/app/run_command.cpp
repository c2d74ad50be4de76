// `covcontact run`: deck -> model -> load stepping -> results file, with progress, signal
// handling (SIGINT/SIGTERM stop after the current iteration) and a closing summary.
#include <fmt/format.h>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <new>
#include <sstream>

#include "app/commands.hpp"
#include "app/progress.hpp"
#include "app/restart.hpp"
#include "common/errors.hpp"
#include "deck/deck_parser.hpp"
#include "model/model.hpp"
#include "output/hdf5_io.hpp"
#include "output/results_file_guard.hpp"
#include "output/results_writer.hpp"
#include "solver/load_stepper.hpp"
#include "verification/reference_report.hpp"
#include "verification/reference_tracker.hpp"

namespace cc::app {

namespace {

std::atomic<bool> stopSignal{false};

// The first SIGINT/SIGTERM stops after the current iteration (which may be a long solve); a
// second one stops at once, like a kill: every step already written stays readable.
extern "C" void requestStop(int) {
  if (!stopSignal.exchange(true)) return;
  static const char kMessage[] =
      "\ncovcontact: second interrupt: stopping at once; the steps written so far are kept\n";
  [[maybe_unused]] const auto written = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
  ::_exit(kExitInterrupted);
}

// What did not fit when memory ran out, with the model's size and the memory the process had
// reached (std::bad_alloc itself says neither).
std::string outOfMemoryMessage(const char* during, const Model* model) {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  std::string text = fmt::format("out of memory while {}", during);
  if (model)
    text += fmt::format(" ({} nodes, {} elements, {} equations)", model->mesh().numNodes(),
                        model->elementCount(), model->dofMap().numFree());
  return text + fmt::format(
                    "; the process had reached {:.2f} GiB; use fewer elements or a "
                    "machine with more memory",
                    static_cast<double>(usage.ru_maxrss) / (1 << 20));
}

// Receives the stepper's records: writes them and reports progress.
class RunObserver : public StepObserver {
 public:
  RunObserver(Model& model, ResultsWriter& writer, Progress& progress, bool withStress,
              verification::ReferenceTracker* references = nullptr)
      : model_(model),
        writer_(writer),
        progress_(progress),
        withStress_(withStress),
        references_(references) {}

  void iteration(const IterationRecord& record) override {
    writer_.appendIteration(record);
    progress_.iteration(record);
  }
  void cutback(const CutbackRecord& record) override {
    writer_.appendCutback(record);
    progress_.cutback(record);
  }
  void note(const std::string& line) override {
    if (line.rfind("linear solver: ", 0) == 0) linearSolver_ = line.substr(15);
    progress_.note(line);
  }
  const std::string& linearSolver() const { return linearSolver_; }
  // The stepper whose next step size the restart data of every written step records.
  void attach(const LoadStepper& stepper) { stepper_ = &stepper; }

  void stepConverged(int step, double time, int iterations, int cutbacks,
                     const Eigen::VectorXd& displacement, const Eigen::VectorXd& internalForce,
                     bool writeOutput) override {
    model_.accountEnergy(time, displacement, internalForce);  // every step: a running sum
    const bool compare = references_ && !references_->empty();
    if (writeOutput || compare) {
      StepRecord record = model_.stepRecord(step, time, iterations, cutbacks, displacement,
                                            internalForce, withStress_ && writeOutput);
      if (writeOutput) {
        const RestartRecord restart =
            restartRecordOf(model_, displacement, stepper_->nextStepSize());
        record.restart = &restart;
        writer_.writeStep(record);
        ++writtenSteps_;
      }
      if (compare) references_->observe(record);  // every converged step, written or not
    }
    progress_.stepConverged(step, time, iterations, cutbacks);
  }
  bool stopRequested() const override { return stopSignal.load(); }
  int writtenSteps() const { return writtenSteps_; }

 private:
  Model& model_;
  ResultsWriter& writer_;
  Progress& progress_;
  bool withStress_;
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

// STEP:ITER of --dump-tangent (checked by the command line parser's validator as well).
TangentDumpRequest parseDumpRequest(const std::string& text) {
  TangentDumpRequest request;
  char colon = 0;
  std::istringstream in(text);
  if (!(in >> request.step >> colon >> request.iteration) || colon != ':' || request.step < 1 ||
      request.iteration < 1 || !in.eof()) {
    throw std::invalid_argument("--dump-tangent expects STEP:ITER (both >= 1), got '" + text + "'");
  }
  return request;
}

int plannedSteps(const ProblemSpec& spec) {
  int steps = 0;
  for (const PhaseSpec& phase : spec.phases) steps += phase.steps;
  return steps;
}

}  // namespace

std::string resultsPath(const std::string& deckPath, const std::string& deckOutput,
                        const std::string& commandLineOutput) {
  if (!commandLineOutput.empty()) return commandLineOutput;
  if (!deckOutput.empty()) return deckOutput;
  return std::filesystem::path(deckPath).stem().string() + ".h5";
}

int runCommand(const RunOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  if (options.threads > 0) omp_set_num_threads(options.threads);
  std::unique_ptr<Model> model;
  std::unique_ptr<verification::ReferenceTracker> references;
  std::string path;
  OutputSelection selection;
  StartState startState;
  std::vector<std::string> inputs;  // files the results must never replace
  try {
    const ProblemSpec spec = parseDeck(options.deck);
    path = resultsPath(options.deck, spec.output.file, options.output);
    selection = outputSelection(spec.output);
    if (!options.restartFile.empty() && sameFile(path, options.restartFile)) {
      std::cerr << "covcontact: error: the results file '" << path
                << "' is the restart file; give another one with -o\n";
      return kExitUsage;
    }
    inputs = spec.deckFiles;
    inputs.push_back(spec.mesh.path);
    if (!options.restartFile.empty()) inputs.push_back(options.restartFile);
    checkOutputWritable(path, selection, inputs);
    model = buildModel(spec);
    references = std::make_unique<verification::ReferenceTracker>(*model);
    if (!options.restartFile.empty())
      startState = restartFrom(options.restartFile, options.restartStep, *model);
  } catch (const InputError& error) {
    std::cerr << error.what() << "\n";
    return kExitInput;
  } catch (const OutputError& error) {
    std::cerr << "covcontact: error: " << error.what() << "\n";
    return kExitIo;
  } catch (const OutOfMemory& error) {
    std::cerr << "covcontact: error: " << error.what() << "\n";
    return kExitOutOfMemory;
  } catch (const std::bad_alloc&) {
    std::cerr << "covcontact: error: "
              << outOfMemoryMessage("reading the mesh and building the model", model.get()) << "\n";
    return kExitOutOfMemory;
  }
  const ProblemSpec& spec = model->spec();
  if (!options.quiet) {
    printOut(fmt::format("{}: {} nodes, {} elements, {} equations, {} contact points, {} threads\n",
                         spec.title.empty() ? options.deck : spec.title, model->mesh().numNodes(),
                         model->elementCount(), model->dofMap().numFree(),
                         model->contactPointCount(), model->threads()));
    for (const auto& pair : model->contactPairs()) {
      const contact::ContactPairConfig& config = pair->config();
      if (config.automaticPenalty) {
        printOut(fmt::format("contact '{}': automatic penalty eps_n = {:.6g}, eps_t = {:.6g}\n",
                             config.name, config.law.penaltyNormal, config.law.penaltyTangential));
      }
    }
    if (!options.restartFile.empty()) {
      printOut(fmt::format("continuing from step {} (t = {:.6g}) of {}\n", startState.step,
                           startState.time, options.restartFile));
    }
  }

  ResultsWriter writer;
  try {
    writer.open(
        path,
        {spec.deckText, options.commandLine, spec.title, COVCONTACT_VERSION, options.deck, inputs},
        model->mesh(), selection);
  } catch (const OutputError& error) {
    std::cerr << "covcontact: error: " << error.what() << "\n";
    return kExitIo;
  }
  Progress progress(plannedSteps(spec), options.quiet, options.newtonLog);
  RunObserver observer(*model, writer, progress, selection.stress, references.get());
  stopSignal.store(false);
  std::signal(SIGINT, requestStop);
  std::signal(SIGTERM, requestStop);
  // Each dump goes to <dir>/<results stem>_tangent_STEP_ITER, <dir> = --dump-dir or the
  // results file's directory.
  std::vector<TangentDumpRequest> dumps;
  for (const std::string& text : options.dumpTangent) {
    TangentDumpRequest dump = parseDumpRequest(text);
    const std::filesystem::path results(path);
    const std::filesystem::path directory = options.dumpDirectory.empty()
                                                ? results.parent_path()
                                                : std::filesystem::path(options.dumpDirectory);
    dump.directory = (directory / fmt::format("{}_tangent_{}_{}", results.stem().string(),
                                              dump.step, dump.iteration))
                         .string();
    dumps.push_back(dump);
  }
  LoadStepper stepper(*model, observer, spec.phases, spec.linearSolver, dumps);
  if (!options.checkTangent.empty()) {
    int step = 0, iteration = 0;
    std::sscanf(options.checkTangent.c_str(), "%d:%d", &step, &iteration);  // validated by CLI
    stepper.setTangentCheck(step, iteration);
  }
  observer.attach(stepper);
  RunSummary summary;
  try {
    summary = stepper.run(startState);
  } catch (const OutputError& error) {
    progress.finish();
    std::cerr << "covcontact: error: " << error.what() << "\n";
    return kExitIo;
  } catch (const InputError& error) {
    // A deck function that fails only when evaluated (an expression that is not finite at some
    // t): the converged steps stay in the file, which is closed with the reason.
    progress.finish();
    std::cerr << error.what() << "\n";
    const SolverStatistics done = stepper.statistics();
    writer.close({"input error", done.steps, done.iterations, done.cutbacks,
                  std::chrono::duration<double>(Clock::now() - start).count(), error.what(),
                  observer.linearSolver(), done.linear.krylovIterations,
                  done.linear.krylovFallbacks});
    return kExitInput;
  } catch (const std::exception& error) {
    // Memory ran out in a step (the factor, an assembly): the converged steps are on disk; the
    // file is closed with the reason, which names what did not fit where it is known.
    const bool outOfMemory = dynamic_cast<const OutOfMemory*>(&error) != nullptr ||
                             dynamic_cast<const std::bad_alloc*>(&error) != nullptr;
    if (!outOfMemory) throw;
    progress.finish();
    const SolverStatistics done = stepper.statistics();
    const std::string message = dynamic_cast<const OutOfMemory*>(&error)
                                    ? std::string(error.what())
                                    : outOfMemoryMessage("solving a step", model.get());
    std::cerr << "covcontact: error: " << message << "\n"
              << keptStepsMessage(done.steps, observer.writtenSteps(), path);
    writer.close({"out of memory", done.steps, done.iterations, done.cutbacks,
                  std::chrono::duration<double>(Clock::now() - start).count(), message,
                  observer.linearSolver(), done.linear.krylovIterations,
                  done.linear.krylovFallbacks});
    return kExitOutOfMemory;
  }
  // The handlers stay until the file is closed: a second interrupt arriving while the run winds
  // up must end it through requestStop (exit 4, file intact), not by the default action.
  progress.finish();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const SolverStatistics work = stepper.statistics();
  writer.close({outcomeName(summary.outcome), summary.stepsConverged, summary.totalIterations,
                summary.totalCutbacks, seconds, summary.message, observer.linearSolver(),
                work.linear.krylovIterations, work.linear.krylovFallbacks,
                summary.lineSearchRetries, summary.discardedIterations});
  if (summary.outcome == RunSummary::Outcome::Completed) {
    // The work of failed attempts (retried with line search or cut back) is not in the
    // iterations of the converged steps; it is said separately.
    const std::string discarded =
        summary.discardedIterations > 0
            ? fmt::format(" (+{} in failed attempts, {} retried with line search)",
                          summary.discardedIterations, summary.lineSearchRetries)
            : std::string();
    printOut(fmt::format(
        "completed: {} steps, {} Newton iterations{}, {} cut-backs in {:.2f} s; results in {}\n",
        summary.stepsConverged, summary.totalIterations, discarded, summary.totalCutbacks, seconds,
        path));
  }
  if (!references->empty()) {
    const verification::RunCost cost{seconds, summary.totalIterations, summary.stepsConverged};
    const auto errors = references->results();
    printOut(verification::formatReferenceErrors(errors, cost));
    try {
      verification::writeReferenceErrors(path, errors, cost);
    } catch (const OutputError& error) {
      std::cerr << "covcontact: error: " << error.what() << "\n";
      return kExitIo;
    }
  }
  if (summary.outcome != RunSummary::Outcome::Completed) {
    std::cerr << fmt::format("covcontact: run {} at t = {:.6g}: {}\n", outcomeName(summary.outcome),
                             summary.finalTime, summary.message)
              << keptStepsMessage(summary.stepsConverged, observer.writtenSteps(), path);
  }
  return exitCodeOf(summary.outcome);
}

}  // namespace cc::app
