// The `covcontact` command: parses the command line (CLI11) and dispatches to run, check and
// compare. Exit codes are listed in --help and in common/errors.hpp.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>

#include "app/commands.hpp"
#include "app/heap_policy.hpp"
#include "app/openmp_environment.hpp"
#include "app/run_environment.hpp"
#include "app/stop_signals.hpp"
#include "common/errors.hpp"
#include "deck/spec_choices.hpp"
#include "parallel/process_group.hpp"
#include "solver/petsc_loader.hpp"

namespace {

const char* kExitCodes = R"(Exit codes:
  0  success (run completed, deck valid, runs match)
  1  bad command line
  2  invalid deck, mesh or include file (the message names file:line)
  3  a step failed after all cut-backs; every converged step is in the results file
  4  interrupted by SIGINT/SIGTERM; every converged step is in the results file
  5  compare: the results differ from the reference
  6  a results file could not be written or read
  7  singular system (e.g. an unconstrained rigid-body motion); converged steps are kept
  8  out of memory (the message says what did not fit); converged steps are kept
 70  internal error (a bug: please report it with the deck))";

std::string joinArguments(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i ? " " : "") + std::string(argv[i]);
  return line;
}

// A whole number from 1 to INT_MAX. CLI::PositiveNumber would say "not in range" and print the
// largest double in full (300 digits) for `--threads 0`.
// CLI11 puts the option's name before the message.
CLI::Validator wholeNumberFromOne() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const long long value = std::stoll(text, &used);
          if (used == text.size() && value >= 1 && value <= std::numeric_limits<int>::max())
            return {};
        } catch (const std::exception&) {
          // not a number, or out of long long's range: the message below
        }
        return fmt::format("must be a whole number from 1 to {}, got '{}'",
                           std::numeric_limits<int>::max(), text);
      },
      "INT>=1");
}

// `covcontact run`: its options, into `options`.
CLI::App* addRunCommand(CLI::App& cli, cc::app::RunOptions& options) {
  auto* command = cli.add_subcommand("run", "Solve the problem a deck describes");
  command->add_option("deck", options.deck, "Input deck")->required()->check(CLI::ExistingFile);
  command->add_option("-o,--output", options.output,
                      "Results file (HDF5; .xdmf and .csv beside it)");
  command->add_option("--threads", options.threads, "Assembly threads (default: all cores)")
      ->check(wholeNumberFromOne());
  command->add_flag("-q,--quiet", options.quiet, "Print only the final summary");
  command->add_flag("--newton-log", options.newtonLog,
                    "Print every Newton iteration: residual, energy, and the contact points "
                    "that changed state or master segment since the previous iteration, "
                    "the sign of the tangent's determinant where a direct solver "
                    "factorized it (det +/-/0: a change marks a limit point passed); "
                    "with an iterative linear solver, its Krylov iterations and tolerance");
  command
      ->add_option("--check-tangent", options.checkTangent,
                   "STEP:ITERATION: compare the assembled tangent with central differences of "
                   "the residual at that iterate (printed to stderr). Use ITERATION >= 2 in "
                   "contact runs: at a step's first iterate some points use a law of that "
                   "iterate only (sliding kept, held closed at a prediction), which the "
                   "differences do not see")
      ->check(CLI::Validator(
          [](std::string& value) {
            int step = 0, iteration = 0;
            char extra = 0;
            return std::sscanf(value.c_str(), "%d:%d%c", &step, &iteration, &extra) == 2 &&
                           step > 0 && iteration > 0
                       ? std::string()
                       : std::string("expected STEP:ITERATION, two positive integers");
          },
          "STEP:ITERATION"));
  auto* restartOption =
      command
          ->add_option("--restart", options.restartFile,
                       "Continue from a converged step stored in this results file (the "
                       "deck and mesh must be those of the run that wrote it)")
          ->check(CLI::ExistingFile);
  command
      ->add_option("--dump-tangent", options.dumpTangent,
                   "Write the Newton system of step STEP, iteration ITER (STEP:ITER) in "
                   "PETSc binary format, with its rigid-body modes (solver/tangent_dump.hpp); "
                   "STEP:ITER:ATTEMPT takes it from a later attempt of the step (0 the first, "
                   "1 the retry after it, ...); repeatable")
      ->check(CLI::Validator(
          [](std::string& value) -> std::string {
            if (cc::app::parseTangentDumpSelection(value)) return {};
            return std::string("expected ") + cc::app::kTangentDumpForm + ", got '" + value + "'";
          },
          "STEP:ITER[:ATTEMPT]"));
  command->add_option(
      "--dump-dir", options.dumpDirectory,
      "Directory in which --dump-tangent writes <results stem>_tangent_STEP_ITER (a later "
      "attempt: _aATTEMPT appended; default: the results file's directory)");
  command
      ->add_option("--solver", options.solver,
                   "Linear solver, overriding the deck's `solve solver=`: auto, cholmod, "
                   "umfpack, mumps, superlu_dist, amg or gamg")
      ->check(CLI::IsMember(cc::deck::choiceNames(cc::deck::linearSolverMethods())));
  command->add_flag("--cost", options.cost,
                    "Print at the end one line `cost: {json}` with where the time went (per "
                    "process under mpirun), peak memory and data moved between processes");
  command
      ->add_option("--from-step", options.restartStep,
                   "Step of the --restart file to continue from (default: its last step)")
      ->check(wholeNumberFromOne())
      ->needs(restartOption);
  return command;
}

// `covcontact check`: a deck to validate, or the keyword list.
struct CheckOptions {
  std::string deck;
  bool listKeywords = false;
};

CLI::App* addCheckCommand(CLI::App& cli, CheckOptions& options) {
  auto* command = cli.add_subcommand("check", "Validate a deck and its mesh without solving");
  command->add_option("deck", options.deck, "Input deck");
  command->add_flag("--keywords", options.listKeywords, "List every deck keyword and parameter");
  return command;
}

CLI::App* addCompareCommand(CLI::App& cli, cc::app::CompareOptionsCli& options) {
  auto* command = cli.add_subcommand("compare",
                                     "Compare a run's results with a reference results file: "
                                     "iteration counts exactly, chosen fields within tolerance");
  command->add_option("run", options.run, "Results file of the run")->required();
  command->add_option("reference", options.reference, "Reference results file")->required();
  command->add_option("--rtol", options.rtol, "Relative tolerance")->capture_default_str();
  command->add_option("--atol", options.atol, "Absolute tolerance (default: 1e-10 x field max)");
  command
      ->add_option("--fields", options.fields,
                   "Datasets per step to compare (default: set_reactions, "
                   "contact/*/total_force)")
      ->delimiter(',');
  return command;
}

CLI::App* addSolveDumpCommand(CLI::App& cli, cc::app::SolveDumpOptions& options) {
  auto* command = cli.add_subcommand(
      "solve-dump",
      "Solve a system written by run --dump-tangent with one linear solver and print what it "
      "cost (one JSON line; scripts/solver_survey.py)");
  command->add_option("directory", options.directory, "Dump directory")
      ->required()
      ->check(CLI::ExistingDirectory);
  command
      ->add_option("--solver", options.solver,
                   "auto, cholmod, umfpack, mumps, superlu_dist, amg or gamg")
      ->capture_default_str();
  command->add_option("--rtol", options.rtol, "Relative residual for the iterative solvers")
      ->capture_default_str();
  return command;
}

}  // namespace

int main(int argc, char** argv) {
  // A closed pipe on stdout (`covcontact run DECK | head -1`) must not kill the run: writes then
  // fail with EPIPE, which printOut reports once, and the run goes on to finish its results.
  std::signal(SIGPIPE, SIG_IGN);
  cc::app::watchStopSignals();
  CLI::App cli{
      "CovContact: 3D frictional contact at large deformations (covariant description, "
      "Konyukhov & Schweizerhof 2005)"};
  cli.footer(kExitCodes);
  cli.require_subcommand(1);
  cli.set_version_flag("--version", COVCONTACT_VERSION);

  cc::app::RunOptions run;
  CLI::App* runCommand = addRunCommand(cli, run);
  CheckOptions check;
  CLI::App* checkCommand = addCheckCommand(cli, check);
  cc::app::CompareOptionsCli compare;
  addCompareCommand(cli, compare);
  cc::app::SolveDumpOptions solveDump;
  CLI::App* solveDumpCommand = addSolveDumpCommand(cli, solveDump);

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = cli.exit(error);
    return code == 0 ? cc::kExitOk : cc::kExitUsage;
  }

  if (*runCommand) {
    run.threads = cc::app::runThreads(run.threads);
    // Started directly rather than through the `covcontact` launcher (app/launcher.cpp), the
    // program sets a run's OpenMP settings and BLAS kernels itself and re-executes itself.
    cc::app::applyRunEnvironment(argv, run.threads);
  }
  cc::app::keepFreedMemory();  // small models; a run of a large one returns it (heap_policy)
  try {
    // PETSc (and MPI) are started by the first PETSc solver only; finalized once here.
    struct PetscFinalizer {
      ~PetscFinalizer() { cc::petsc::finalize(); }
    } petscFinalizer;
    if (*runCommand) {
      run.commandLine = joinArguments(argc, argv);
      return cc::app::runCommand(run);
    }
    // solve-dump's PETSc solvers would start on all the launched processes' communicator while
    // only one process solves: under mpirun it waited for the others for ever.
    if (*solveDumpCommand && cc::launchedProcesses() > 1) {
      // The other processes leave quietly: a non-zero exit of theirs had mpirun end process 0
      // before it printed why.
      if (cc::launchedRank() != 0) return cc::kExitOk;
      std::cerr << "covcontact solve-dump: solves a dump on one process; run it without mpirun "
                   "(or with -np 1)\n";
      return cc::kExitUsage;
    }
    // check and compare work on one process: under mpirun rank 0 does the work and the others
    // leave at once (otherwise the output came once per process).
    if (cc::launchedProcesses() > 1 && cc::launchedRank() != 0) return cc::kExitOk;
    if (*solveDumpCommand) return cc::app::solveDumpCommand(solveDump);
    if (*checkCommand) {
      if (check.deck.empty() && !check.listKeywords) {
        std::cerr << "covcontact check: give a deck (or --keywords)\n";
        return cc::kExitUsage;
      }
      return cc::app::checkCommand(check.deck, check.listKeywords);
    }
    return cc::app::compareCommand(compare);
  } catch (const std::exception& error) {
    std::cerr << "covcontact: internal error: " << error.what() << "\n";
    return cc::kExitInternal;
  }
}
