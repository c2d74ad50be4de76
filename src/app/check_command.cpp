// `covcontact check`: parse the deck, load the mesh and build the model without solving, and
// check that the results file can be written.
#include <fmt/format.h>

#include <iostream>

#include "app/commands.hpp"
#include "common/errors.hpp"
#include "deck/deck_parser.hpp"
#include "model/model.hpp"
#include "output/hdf5_io.hpp"
#include "output/results_writer.hpp"
#include "verification/reference_tracker.hpp"

namespace cc::app {

int checkCommand(const std::string& deck, bool listKeywords) {
  if (listKeywords) {
    fmt::print("{}", keywordListing());
    if (deck.empty()) return kExitOk;
  }
  try {
    const ProblemSpec spec = parseDeck(deck);
    const std::string path = resultsPath(deck, spec.output.file, "");
    // Checked without creating anything (check writes no files).
    std::vector<std::string> inputs = spec.deckFiles;  // a results file must not replace them
    inputs.push_back(spec.mesh.path);
    checkOutputWritable(path, {}, inputs);
    const auto model = buildModel(spec);
    const verification::ReferenceTracker references(*model);  // checks the `reference` lines
    fmt::print(
        "{}: valid. {} nodes, {} elements, {} equations, {} prescribed dofs, {} contact "
        "pairs with {} points, {} phases\n",
        deck, model->mesh().numNodes(), model->elementCount(), model->dofMap().numFree(),
        model->dofMap().numPrescribed(), model->contactPairs().size(), model->contactPointCount(),
        spec.phases.size());
  } catch (const InputError& error) {
    std::cerr << error.what() << "\n";
    return kExitInput;
  } catch (const OutputError& error) {
    std::cerr << "covcontact: error: " << error.what() << "\n";
    return kExitIo;
  }
  return kExitOk;
}

}  // namespace cc::app
