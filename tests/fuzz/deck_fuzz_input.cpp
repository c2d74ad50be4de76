// Parsing one fuzz input (see deck_fuzz_input.hpp).
#include "deck_fuzz_input.hpp"

#include <string>

#include "common/errors.hpp"
#include "deck/deck_parser.hpp"

namespace cc::fuzz {

namespace {

// The deck's virtual location: beside the bad decks, so that the relative paths the seeds use
// (`../meshes/cube.geo`, `inc/cycle_a.inc`, ...) resolve to real files and the parser gets past
// the mesh and include lines to everything after them. The parser only checks that a mesh file
// exists and reads include files; it writes nothing.
constexpr const char* kVirtualPath = COVCONTACT_SOURCE_DIR "/tests/decks/bad/fuzz.deck";

}  // namespace

bool parseDeckBytes(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    parseDeckText(text, kVirtualPath);
    return true;
  } catch (const InputError&) {
    return false;  // the expected way to reject a malformed deck
  }
}

}  // namespace cc::fuzz
