// The state of a deck being read: the ProblemSpec built so far, the sticky solve settings, and
// the name references that can only be checked once every line is read. Keyword handlers (one
// per keyword, named in the declaration table) fill it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "deck/parsed_line.hpp"
#include "spec/problem_spec.hpp"

namespace cc::deck {

// A name used on one line that must be defined somewhere in the deck.
struct NameUse {
  std::string name;
  SourceLocation where;
  std::string context;  // "elements 'block'"
  std::string role;     // what the name is used as: "material", "master", "slave"
  std::string kind;     // contact uses: the pair kind (sts, nts, stas)
};

struct DeckState {
  ProblemSpec spec;

  std::optional<SourceLocation> titleAt;
  std::optional<SourceLocation> meshAt;
  std::optional<SourceLocation> outputAt;
  std::optional<SourceLocation> solveAt;  // the `solve` line, once seen
  bool insideSolve = false;

  // FEAP-style sticky solve settings: a `newton` or `cutback` line changes them for every later
  // phase; a `steps` line copies them into its phase (overriding some for that phase only).
  NewtonSpec newton;
  CutbackSpec cutback;

  std::vector<NameUse> materialUses;  // elements material=
  std::vector<NameUse> rigidUses;     // stas slave=: must be a rigid surface
  std::vector<NameUse> faceSetUses;   // other master=/slave=: must not be a rigid surface
};

// Model keywords (model_keywords.cpp, contact_keywords.cpp).
void handleTitle(const ParsedLine& line, DeckState& state);
void handleMesh(const ParsedLine& line, DeckState& state);
void handleMaterial(const ParsedLine& line, DeckState& state);
void handleElements(const ParsedLine& line, DeckState& state);
void handleFix(const ParsedLine& line, DeckState& state);
void handlePrescribe(const ParsedLine& line, DeckState& state);
void handleLoad(const ParsedLine& line, DeckState& state);
void handleOutput(const ParsedLine& line, DeckState& state);
void handleReference(const ParsedLine& line, DeckState& state);
void handleRigid(const ParsedLine& line, DeckState& state);
void handleContact(const ParsedLine& line, DeckState& state);

// Solve block (solve_keywords.cpp).
void handleSolve(const ParsedLine& line, DeckState& state);
void handleEnd(const ParsedLine& line, DeckState& state);
void handleNewton(const ParsedLine& line, DeckState& state);
void handleCutback(const ParsedLine& line, DeckState& state);
void handleSteps(const ParsedLine& line, DeckState& state);

// Checks that need the whole deck (deck_validation.cpp): a mesh, elements and a solve block
// exist, the solve block is closed, and every referenced material or rigid surface is defined.
void validateDeck(const DeckState& state, const std::string& deckPath);

}  // namespace cc::deck
