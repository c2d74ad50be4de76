// Checks that need the whole deck: required blocks present, the solve block closed, and names
// used before or after their definition (materials, rigid surfaces) resolved.
#include <fmt/format.h>

#include <algorithm>

#include "common/errors.hpp"
#include "common/name_matching.hpp"
#include "deck/deck_state.hpp"

namespace cc::deck {

namespace {

std::vector<std::string> materialNames(const ProblemSpec& spec) {
  std::vector<std::string> names;
  for (const MaterialSpec& material : spec.materials) names.push_back(material.name);
  return names;
}

std::vector<std::string> rigidNames(const ProblemSpec& spec) {
  std::vector<std::string> names;
  for (const RigidSurfaceSpec& rigid : spec.rigidSurfaces) names.push_back(rigid.name);
  return names;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// "; did you mean 'x'?", or the defined names, or that there are none.
std::string definedHint(const std::string& name, const std::vector<std::string>& defined,
                        const std::string& what) {
  if (defined.empty()) return fmt::format(" (the deck defines no {})", what);
  const std::string suggestion = didYouMean(name, defined);
  if (!suggestion.empty()) return suggestion;
  std::string list;
  for (const std::string& item : defined) list += (list.empty() ? "" : ", ") + item;
  return fmt::format(" (the deck defines: {})", list);
}

[[noreturn]] void failUse(const NameUse& use, const std::string& message) {
  throw InputError(use.where, use.context + ": " + message);
}

void checkRequiredBlocks(const DeckState& state, const std::string& deckPath) {
  const SourceLocation deck{deckPath, 0, 0};
  if (state.insideSolve) {
    throw InputError(*state.solveAt,
                     "the solve block is never closed; add 'end' after its "
                     "last command");
  }
  if (!state.meshAt) {
    throw InputError(deck, "no mesh: add a line such as 'mesh \"block.geo\"'");
  }
  if (state.spec.elementBlocks.empty()) {
    throw InputError(deck, "no elements: add a line such as 'elements GROUP hex8 material=NAME'");
  }
  if (!state.solveAt) {
    throw InputError(deck, "no solve block: add 'solve', a line 'steps N dt=D' and 'end'");
  }
}

}  // namespace

void validateDeck(const DeckState& state, const std::string& deckPath) {
  checkRequiredBlocks(state, deckPath);
  const std::vector<std::string> materials = materialNames(state.spec);
  for (const NameUse& use : state.materialUses) {
    if (!contains(materials, use.name)) {
      failUse(use, fmt::format("undefined material '{}'{}", use.name,
                               definedHint(use.name, materials, "material")));
    }
  }
  const std::vector<std::string> rigids = rigidNames(state.spec);
  for (const NameUse& use : state.rigidUses) {
    if (!contains(rigids, use.name)) {
      failUse(use, fmt::format("an {} pair needs a 'rigid' surface as its {}, but '{}' is not "
                               "one{}",
                               use.kind, use.role, use.name,
                               definedHint(use.name, rigids, "rigid surface")));
    }
  }
  for (const NameUse& use : state.faceSetUses) {
    if (contains(rigids, use.name)) {
      failUse(use, fmt::format("{} '{}' is a rigid surface, but an {} pair needs a face set of "
                               "the mesh here (a rigid surface can only be the slave of an "
                               "stas pair)",
                               use.role, use.name, use.kind));
    }
  }
}

}  // namespace cc::deck
