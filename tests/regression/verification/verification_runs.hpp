// Test support for verification decks: run a deck of input/verification with changed mesh
// parameters, penalties or step counts, and return the errors of its `reference` lines.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "deck_runner.hpp"
#include "verification/reference_tracker.hpp"

namespace cc::test {

struct DeckChanges {
  std::map<std::string, std::string> mesh;  // NAME=VALUE on the mesh line
  double penaltyScale = 1;                  // multiplies eps_n and eps_t of every contact line
  std::vector<std::pair<std::string, std::string>> replace;  // every occurrence, literally
};

// The deck text with the changes applied (throws std::invalid_argument if a replacement or a
// mesh parameter is not found, so a renamed deck parameter cannot silently leave a test stale).
std::string changedDeck(const std::string& deckPath, const DeckChanges& changes);

struct VerifiedRun {
  DeckRun run;
  std::map<std::string, verification::ReferenceResult> errors;  // by quantity
  const verification::ReferenceResult& operator[](const std::string& quantity) const;
};

// Runs the deck file (with changes) in-process and evaluates its references on every step.
VerifiedRun runVerificationDeck(const std::string& deckPath, const DeckChanges& changes = {});

}  // namespace cc::test
