// The `covcontact` command: parses the command line (CLI11) and dispatches to run, check and
// compare. Exit codes are listed in --help and in common/errors.hpp.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <iostream>
#include <limits>

#include "app/commands.hpp"
#include "common/errors.hpp"

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

}  // namespace

int main(int argc, char** argv) {
  // A closed pipe on stdout (`covcontact run DECK | head -1`) must not kill the run: writes then
  // fail with EPIPE, which printOut reports once, and the run goes on to finish its results.
  std::signal(SIGPIPE, SIG_IGN);
  CLI::App cli{
      "CovContact: 3D frictional contact at large deformations (covariant description, "
      "Konyukhov & Schweizerhof 2005)"};
  cli.footer(kExitCodes);
  cli.require_subcommand(1);
  cli.set_version_flag("--version", COVCONTACT_VERSION);

  cc::app::RunOptions run;
  auto* runCommand = cli.add_subcommand("run", "Solve the problem a deck describes");
  runCommand->add_option("deck", run.deck, "Input deck")->required()->check(CLI::ExistingFile);
  runCommand->add_option("-o,--output", run.output,
                         "Results file (HDF5; .xdmf and .csv beside it)");
  runCommand->add_option("--threads", run.threads, "Assembly threads (default: all cores)")
      ->check(wholeNumberFromOne());
  runCommand->add_flag("-q,--quiet", run.quiet, "Print only the final summary");
  auto* restartOption =
      runCommand
          ->add_option("--restart", run.restartFile,
                       "Continue from a converged step stored in this results file (the "
                       "deck and mesh must be those of the run that wrote it)")
          ->check(CLI::ExistingFile);
  runCommand
      ->add_option("--from-step", run.restartStep,
                   "Step of the --restart file to continue from (default: its last step)")
      ->check(wholeNumberFromOne())
      ->needs(restartOption);

  std::string checkDeck;
  bool listKeywords = false;
  auto* checkCommand = cli.add_subcommand("check", "Validate a deck and its mesh without solving");
  checkCommand->add_option("deck", checkDeck, "Input deck");
  checkCommand->add_flag("--keywords", listKeywords, "List every deck keyword and parameter");

  cc::app::CompareOptionsCli compare;
  auto* compareCommand =
      cli.add_subcommand("compare",
                         "Compare a run's results with a reference results file: "
                         "iteration counts exactly, chosen fields within tolerance");
  compareCommand->add_option("run", compare.run, "Results file of the run")->required();
  compareCommand->add_option("reference", compare.reference, "Reference results file")->required();
  compareCommand->add_option("--rtol", compare.rtol, "Relative tolerance")->capture_default_str();
  compareCommand->add_option("--atol", compare.atol,
                             "Absolute tolerance (default: 1e-10 x field max)");
  compareCommand
      ->add_option("--fields", compare.fields,
                   "Datasets per step to compare (default: set_reactions, "
                   "contact/*/total_force)")
      ->delimiter(',');

  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = cli.exit(error);
    return code == 0 ? cc::kExitOk : cc::kExitUsage;
  }

  try {
    if (*runCommand) {
      run.commandLine = joinArguments(argc, argv);
      return cc::app::runCommand(run);
    }
    if (*checkCommand) {
      if (checkDeck.empty() && !listKeywords) {
        std::cerr << "covcontact check: give a deck (or --keywords)\n";
        return cc::kExitUsage;
      }
      return cc::app::checkCommand(checkDeck, listKeywords);
    }
    return cc::app::compareCommand(compare);
  } catch (const std::exception& error) {
    std::cerr << "covcontact: internal error: " << error.what() << "\n";
    return cc::kExitInternal;
  }
}
