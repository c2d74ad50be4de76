// Helpers shared by the deck tests: fixture paths and capturing the InputError of a bad deck.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "common/errors.hpp"
#include "deck/deck_parser.hpp"

namespace cc::test {

// A virtual deck next to tests/decks/meshes/, so that `mesh "meshes/cube.geo"` resolves.
inline std::string virtualDeckPath(const std::string& name = "test.deck") {
  return std::string(COVCONTACT_SOURCE_DIR) + "/tests/decks/" + name;
}

inline std::string unitDataPath(const std::string& name) {
  return std::string(COVCONTACT_SOURCE_DIR) + "/tests/unit/deck/data/" + name;
}

// A small valid deck (7 lines) that error tests extend or modify.
inline const std::string kMinimalDeck =
    "mesh \"meshes/cube.geo\"\n"
    "material steel svk E=200 nu=0.3\n"
    "elements cube hex8 material=steel\n"
    "fix bottom all\n"
    "solve\n"
    "  steps 1 dt=1\n"
    "end\n";

// The InputError that parsing `text` must throw (a test failure if it does not).
inline InputError parseError(const std::string& text, const std::string& path = virtualDeckPath()) {
  try {
    parseDeckText(text, path);
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "deck parsed without error:\n" << text;
  return InputError(SourceLocation{}, "<no error>");
}

}  // namespace cc::test
