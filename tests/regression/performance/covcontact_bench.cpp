// covcontact_bench: runs a deck exactly as `covcontact run` does (parse, mesh, model, load
// stepping, HDF5 results; the same OpenMP settings, BLAS kernels and heap policy, from
// app/run_environment.hpp and app/heap_policy.hpp) and prints one JSON object with the cost
// split of the run: element assembly, contact search, contact kernel, pattern rebuilds,
// linear-solver analysis, factorization and solve, output, and the work counters.
// scripts/bench.py drives it.
//
//   covcontact_bench DECK [-o RESULTS.h5] [--threads N] [--solver NAME]
// (--solver as `covcontact run --solver`: scripts/bench.py's memory part runs the direct solvers
// at 232 k, where the deck's solver=auto solves iteratively and no factor exists.)
//   covcontact_bench DECK --orderings [--threads N]
// The second form assembles the deck's first tangent (contact included) and factorizes it with
// CHOLMOD under each fill-reducing ordering (AMD, METIS, NESDIS), one JSON object per ordering.
//   covcontact_bench DECK --search
// The third form times only the contact search (ContactPair::prepare) of every pair: once at
// the reference configuration (every point searched through the bucket grid), then at master
// surfaces slid by a fraction of a segment per call (grid rebuilt, local walks to neighbours).
// Under callgrind only these searches are instrumented.
#include <fmt/format.h>
#include <omp.h>
// Callgrind's client requests (no-ops outside valgrind): the instruction-count check runs
// valgrind with --instr-atstart=no and counts the contact search only, not the meshing.
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#else
#define CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_STOP_INSTRUMENTATION
#endif

#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include "app/heap_policy.hpp"
#include "app/openmp_environment.hpp"
#include "app/run_environment.hpp"
#include "common/errors.hpp"
#include "deck/deck_parser.hpp"
#include "deck/spec_choices.hpp"
#include "model/model.hpp"
#include "output/results_writer.hpp"
#include "solver/linear_solver.hpp"
#include "solver/load_stepper.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The run command's observer without the progress line: writes every record and times it.
class TimedWriterObserver : public cc::StepObserver {
 public:
  TimedWriterObserver(cc::Model& model, cc::ResultsWriter& writer, bool withStress)
      : model_(model), writer_(writer), withStress_(withStress) {}

  void iteration(const cc::IterationRecord& record) override {
    const auto start = Clock::now();
    writer_.appendIteration(record);
    outputSeconds += secondsSince(start);
  }
  void cutback(const cc::CutbackRecord& record) override {
    const auto start = Clock::now();
    writer_.appendCutback(record);
    outputSeconds += secondsSince(start);
  }
  void stepConverged(int step, double time, int iterations, int cutbacks,
                     const Eigen::VectorXd& displacement, const Eigen::VectorXd& internalForce,
                     bool writeOutput) override {
    if (!writeOutput) return;
    const auto start = Clock::now();
    writer_.writeStep(model_.stepRecord(step, time, iterations, cutbacks, displacement,
                                        internalForce, withStress_));
    outputSeconds += secondsSince(start);
    ++stepsWritten;
  }

  double outputSeconds = 0;
  int stepsWritten = 0;

 private:
  cc::Model& model_;
  cc::ResultsWriter& writer_;
  bool withStress_;
};

struct Options {
  std::string deck;
  std::string output;
  int threads = 0;
  // Overrides the deck's `solve solver=` (the memory target's direct run).
  std::optional<cc::LinearSolverSpec::Method> solver;
  bool orderings = false;
  bool search = false;
};

Options parseOptions(int argc, char** argv) {
  Options options;
  for (int k = 1; k < argc; ++k) {
    const std::string argument = argv[k];
    const bool hasValue = k + 1 < argc;
    if (argument == "-o" && hasValue) {
      options.output = argv[++k];
    } else if (argument == "--orderings") {
      options.orderings = true;
    } else if (argument == "--search") {
      options.search = true;
    } else if (argument == "--threads" && hasValue) {
      options.threads = std::stoi(argv[++k]);
    } else if (argument == "--solver" && hasValue) {
      options.solver = cc::deck::choiceValue(cc::deck::linearSolverMethods(), argv[++k]);
    } else if (options.deck.empty() && !argument.starts_with("-")) {
      options.deck = argument;
    } else {
      throw std::invalid_argument("unexpected argument '" + argument + "'");
    }
  }
  if (options.deck.empty()) {
    throw std::invalid_argument(
        "usage: covcontact_bench DECK [-o RESULTS.h5 | --orderings | --search] [--threads N] "
        "[--solver NAME]");
  }
  return options;
}

// Bytes of the mesh arrays (coordinates, element and face connectivity, node sets).
double meshBytes(const cc::Mesh& mesh) {
  double bytes = static_cast<double>(mesh.coordinates.size()) * sizeof(double);
  for (const cc::ElementBlock& block : mesh.blocks) {
    bytes += static_cast<double>(block.connectivity.size()) * sizeof(int);
  }
  for (const auto& [name, faces] : mesh.faceSets) {
    bytes +=
        static_cast<double>(faces.connectivity.size() + 2 * faces.ownerBlock.size()) * sizeof(int);
  }
  for (const auto& [name, set] : mesh.nodeSets) {
    bytes += static_cast<double>(set.nodes.size()) * sizeof(int);
  }
  return bytes;
}

// Prepare and evaluate time of the element sets and of the contact pairs (the model hands the
// assembler its element sets first, then its contact pairs).
struct PartSeconds {
  double elements = 0, contactSearch = 0, contactKernel = 0;
};

PartSeconds partsOf(const cc::Model& model) {
  PartSeconds parts;
  const auto& byContribution = model.assemblyTimings().byContribution;
  const std::size_t elementSets = model.elementSets().size();
  for (std::size_t c = 0; c < byContribution.size(); ++c) {
    if (c < elementSets) {
      parts.elements += byContribution[c].prepare + byContribution[c].evaluate;
    } else {
      parts.contactSearch += byContribution[c].prepare;
      parts.contactKernel += byContribution[c].evaluate;
    }
  }
  return parts;
}

// The tangent at the start of the first step (zero displacement, t = first step's end).
cc::SystemMatrices firstTangent(cc::Model& model) {
  const Eigen::Matrix3Xd& reference = model.referenceCoordinates();
  cc::AssemblyState state;
  state.time = model.spec().phases.front().dt;
  state.previousTime = 0;
  state.reference = &reference;
  state.current = &reference;
  state.previous = &reference;
  cc::SystemMatrices tangent;
  Eigen::VectorXd force;
  model.assemble(state, force, &tangent);
  return tangent;
}

int compareOrderings(const Options& options) {
  if (options.threads > 0) omp_set_num_threads(options.threads);
  std::unique_ptr<cc::Model> model = cc::buildModel(cc::parseDeck(options.deck));
  const cc::SystemMatrices tangent = firstTangent(*model);
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(tangent.free.rows());
  const std::pair<const char*, cc::FillOrdering> orderings[] = {
      {"amd", cc::FillOrdering::Amd},
      {"metis", cc::FillOrdering::Metis},
      {"nesdis", cc::FillOrdering::NestedDissection}};
  for (const auto& [name, ordering] : orderings) {
    std::unique_ptr<cc::LinearSolver> solver = cc::makeCholmodSolver(ordering);
    solver->analyzePattern(tangent.free);
    solver->factorize(tangent.free);
    const Eigen::VectorXd solution = solver->solve(rhs);
    const cc::LinearSolverStatistics& statistics = solver->statistics();
    fmt::print(
        "{{\"deck\": \"{}\", \"ordering\": \"{}\", \"threads\": {}, \"free_dofs\": {}, "
        "\"matrix_nonzeros\": {}, \"factor_bytes\": {:.0f}, \"factor_flops\": {:.0f}, "
        "\"analysis\": {:.6f}, "
        "\"factorization\": {:.6f}, \"triangular_solve\": {:.6f}, \"residual\": {:.3g}}}\n",
        options.deck, name, omp_get_max_threads(), tangent.free.rows(), tangent.free.nonZeros(),
        statistics.largestFactorBytes, statistics.largestFactorFlops, statistics.analysisSeconds,
        statistics.factorizationSeconds, statistics.solveSeconds,
        (tangent.free * solution - rhs).norm() / rhs.norm());
  }
  return 0;
}

// Master-surface slides per timed search call, and the slide per call in segment sizes: enough
// to move every point onto the next segment now and then, as sliding does.
constexpr int kSearchSlides = 4;
constexpr double kSlidePerCall = 0.3;

int timeSearch(const Options& options) {
  std::unique_ptr<cc::Model> model = cc::buildModel(cc::parseDeck(options.deck));
  const Eigen::Matrix3Xd& reference = model->referenceCoordinates();
  for (std::size_t p = 0; p < model->contactPairs().size(); ++p) {
    cc::contact::ContactPair& pair = *model->contactPairs()[p];
    const cc::FaceSet& master = model->mesh().faceSets.at(model->spec().contacts[p].master);
    const double segment =
        (reference.col(master.connectivity(0, 1)) - reference.col(master.connectivity(0, 0)))
            .norm();
    Eigen::Matrix3Xd current = reference;
    cc::AssemblyState state;
    state.reference = &reference;
    state.previous = &reference;
    state.current = &current;
    auto start = Clock::now();
    CALLGRIND_START_INSTRUMENTATION;
    pair.prepare(state);
    CALLGRIND_STOP_INSTRUMENTATION;
    const double initialSeconds = secondsSince(start);
    double slideSeconds = 0;
    for (int slide = 1; slide <= kSearchSlides; ++slide) {
      for (Eigen::Index k = 0; k < master.connectivity.size(); ++k) {
        current(0, master.connectivity.data()[k]) =
            reference(0, master.connectivity.data()[k]) + slide * kSlidePerCall * segment;
      }
      state.previousTime = state.time;
      state.time = slide;
      start = Clock::now();
      CALLGRIND_START_INSTRUMENTATION;
      pair.prepare(state);
      CALLGRIND_STOP_INSTRUMENTATION;
      slideSeconds += secondsSince(start);
    }
    fmt::print(
        "{{\"deck\": \"{}\", \"pair\": \"{}\", \"contact_points\": {}, "
        "\"master_segments\": {}, \"initial_search\": {:.6f}, \"slide_search\": {:.6f}}}\n",
        options.deck, pair.name(), pair.pointCount(), master.connectivity.rows(), initialSeconds,
        slideSeconds / kSearchSlides);
  }
  return 0;
}

int run(const Options& options) {
  const auto start = Clock::now();
  if (options.threads > 0) omp_set_num_threads(options.threads);
  cc::ProblemSpec spec = cc::parseDeck(options.deck);
  if (options.solver) spec.linearSolver.method = *options.solver;
  const std::string path = options.output.empty()
                               ? std::filesystem::path(options.deck).stem().string() + ".h5"
                               : options.output;
  const cc::OutputSelection selection = cc::outputSelection(spec.output);
  std::unique_ptr<cc::Model> model = cc::buildModel(spec);
  cc::app::chooseHeapPolicy(static_cast<std::size_t>(model->dofMap().numFree()));
  const double setupSeconds = secondsSince(start);

  cc::ResultsWriter writer;
  std::vector<std::string> inputFiles = spec.deckFiles;  // never replaced by the results
  inputFiles.push_back(spec.mesh.path);
  auto outputStart = Clock::now();
  writer.open(
      path, {spec.deckText, options.deck, spec.title, COVCONTACT_VERSION, options.deck, inputFiles},
      model->mesh(), selection);
  double openCloseSeconds = secondsSince(outputStart);
  TimedWriterObserver observer(*model, writer, selection.stress);
  cc::LoadStepper stepper(*model, observer, model->spec().phases,
                          spec.linearSolver);  // the deck's solve solver= or --solver
  const auto solveStart = Clock::now();
  const cc::RunSummary summary = stepper.run();
  const double solveSeconds = secondsSince(solveStart);
  outputStart = Clock::now();
  cc::RunTotals totals;
  totals.outcome = summary.outcome == cc::RunSummary::Outcome::Completed ? "completed" : "failed";
  totals.steps = summary.stepsConverged;
  totals.totalIterations = summary.totalIterations;
  totals.cutbacks = summary.totalCutbacks;
  totals.wallSeconds = secondsSince(start);
  totals.message = summary.message;
  writer.close(totals);
  openCloseSeconds += secondsSince(outputStart);
  const double totalSeconds = secondsSince(start);

  const cc::SolverStatistics statistics = stepper.statistics();
  const cc::AssemblyTimings& assembly = model->assemblyTimings();
  const PartSeconds parts = partsOf(*model);
  const cc::LinearSolverStatistics& linear = statistics.linear;
  fmt::print(
      "{{\"deck\": \"{}\", \"completed\": {}, \"message\": \"{}\", \"threads\": {}, "
      "\"nodes\": {}, \"elements\": {}, \"dofs\": {}, \"free_dofs\": {}, \"contact_points\": {}, "
      "\"steps\": {}, \"iterations\": {}, \"cutbacks\": {}, \"assemblies\": {}, "
      "\"factor_bytes\": {:.0f}, \"factor_flops\": {:.0f}, \"mesh_bytes\": {:.0f}, \"analyses\": "
      "{}, \"factorizations\": {}, \"reused_factors\": {}, "
      "\"solves\": {}, "
      "\"cholesky_fallbacks\": {}, \"pattern_builds\": {}, \"pattern_versions\": {}, "
      "\"colorings\": {}, \"steps_written\": {}, "
      "\"seconds\": {{\"total\": {:.6f}, \"setup\": {:.6f}, \"solve_loop\": {:.6f}, "
      "\"element_assembly\": {:.6f}, \"contact_search\": {:.6f}, \"contact_kernel\": {:.6f}, "
      "\"pattern\": {:.6f}, \"assembly_total\": {:.6f}, \"analysis\": {:.6f}, "
      "\"factorization\": {:.6f}, \"triangular_solve\": {:.6f}, \"output\": {:.6f}}}}}\n",
      options.deck, summary.outcome == cc::RunSummary::Outcome::Completed ? "true" : "false",
      summary.message, omp_get_max_threads(), model->mesh().numNodes(), model->elementCount(),
      3 * model->mesh().numNodes(), model->dofMap().numFree(), model->contactPointCount(),
      summary.stepsConverged, summary.totalIterations, summary.totalCutbacks, statistics.assemblies,
      linear.largestFactorBytes, linear.largestFactorFlops, meshBytes(model->mesh()),
      linear.analyses, linear.factorizations, linear.reusedPreconditioners, linear.solves,
      statistics.choleskyFallbacks, assembly.patternBuilds, assembly.patternVersions,
      assembly.colorings, observer.stepsWritten, totalSeconds, setupSeconds, solveSeconds,
      parts.elements, parts.contactSearch, parts.contactKernel, assembly.pattern,
      statistics.assemblySeconds, linear.analysisSeconds, linear.factorizationSeconds,
      linear.solveSeconds, observer.outputSeconds + openCloseSeconds);
  return summary.outcome == cc::RunSummary::Outcome::Completed ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options options = parseOptions(argc, argv);
    // The search timing runs alone (and under callgrind, where a re-execution would leave the
    // instrumented process).
    if (options.search) return timeSearch(options);
    // As the engine: the run's OpenMP settings and BLAS kernels (one re-execution), then the
    // heap that keeps freed memory for small models. Without them this driver ran OpenBLAS's
    // fallback kernels on CPUs OpenBLAS does not know, and mmap-ed UMFPACK's workspace anew at
    // every factorization (docs/performance/solvers.md, twenty-fifth session).
    cc::app::applyRunEnvironment(argv, cc::app::runThreads(options.threads));
    cc::app::keepFreedMemory();
    return options.orderings ? compareOrderings(options) : run(options);
  } catch (const cc::InputError& error) {
    std::cerr << error.what() << "\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "covcontact_bench: " << error.what() << "\n";
    return 3;
  }
}
