// `covcontact compare RUN REFERENCE`: iteration counts exactly, chosen fields within tolerance.
#include <fmt/format.h>

#include <iostream>

#include "app/commands.hpp"
#include "common/errors.hpp"
#include "output/compare.hpp"
#include "output/hdf5_io.hpp"

namespace cc::app {

int compareCommand(const CompareOptionsCli& cli) {
  CompareOptions options;
  options.rtol = cli.rtol;
  options.atol = cli.atol;
  if (!cli.fields.empty()) options.fields = cli.fields;
  try {
    const CompareResult result = compareRuns(cli.run, cli.reference, options);
    fmt::print("{}", result.report);
    return result.match ? kExitOk : kExitMismatch;
  } catch (const OutputError& error) {
    std::cerr << "covcontact compare: error: " << error.what() << "\n";
    return kExitIo;
  }
}

}  // namespace cc::app
