// Deck parsing driver: reads the files, dispatches each line to its keyword's handler in the
// right block (model or solve), then runs the whole-deck checks.
#include "deck/deck_parser.hpp"

#include <fmt/format.h>

#include "common/errors.hpp"
#include "common/name_matching.hpp"
#include "deck/deck_source.hpp"
#include "deck/deck_state.hpp"
#include "deck/solve_parameters.hpp"

namespace cc {

namespace {

using deck::KeywordDecl;

const KeywordDecl& findKeyword(const deck::Token& word) {
  const std::vector<std::string> names = deck::keywordNames();
  const deck::NameMatch match = deck::matchName(word.text, names);
  if (!match.ambiguousWith.empty()) {
    std::vector<std::string> candidates;
    for (int index : match.ambiguousWith) candidates.push_back(names[index]);
    throw InputError(word.where, fmt::format("ambiguous keyword '{}': could be {}", word.text,
                                             deck::joinAlternatives(candidates)));
  }
  if (!match.found()) {
    const std::string hint = deck::didYouMean(word.text, names);
    throw InputError(
        word.where,
        fmt::format("unknown keyword '{}'{}", word.text,
                    hint.empty() ? "; 'covcontact check --keywords' lists them all" : hint));
  }
  return deck::keywordTable()[match.index];
}

// A keyword in the wrong block is an error naming where the block starts or that it is missing.
void checkBlock(const KeywordDecl& keyword, const deck::Token& word, const deck::DeckState& state) {
  using Block = KeywordDecl::Block;
  if (keyword.block == Block::Model && state.insideSolve) {
    throw InputError(word.where,
                     fmt::format("'{}' describes the model and cannot appear inside the solve "
                                 "block (opened at {}); close the block with 'end' first",
                                 keyword.name, state.solveAt->str()));
  }
  if (keyword.block == Block::Solve && !state.insideSolve) {
    if (keyword.name == "end") {
      throw InputError(word.where, "'end' without a matching 'solve'");
    }
    throw InputError(word.where, fmt::format("'{}' belongs inside the solve block: write it "
                                             "between 'solve' and 'end'",
                                             keyword.name));
  }
}

void dispatch(const deck::LogicalLine& line, deck::DeckState& state) {
  const deck::Token& first = line.tokens.front();
  if (!first.isWord()) {
    throw InputError(first.where, fmt::format("expected a keyword at the start of the line, "
                                              "got {}",
                                              deck::describe(first)));
  }
  const KeywordDecl& keyword = findKeyword(first);
  checkBlock(keyword, first, state);
  const deck::ParsedLine parsed(line, keyword);
  keyword.handler(parsed, state);
}

}  // namespace

ProblemSpec parseDeckText(const std::string& text, const std::string& virtualPath) {
  const deck::DeckSource source = deck::loadDeckSource(text, virtualPath);
  deck::DeckState state;
  state.newton = NewtonSpec{};  // the defaults, written once in spec/problem_spec.hpp
  state.cutback = CutbackSpec{};
  state.spec.deckPath = virtualPath;
  state.spec.deckText = source.text;
  state.spec.deckFiles = source.files;
  for (const deck::LogicalLine& line : source.lines) dispatch(line, state);
  deck::validateDeck(state, virtualPath);
  deck::resolveNewtonDefaults(state.spec);
  return std::move(state.spec);
}

ProblemSpec parseDeck(const std::string& path) {
  const std::string text =
      deck::readDeckFile(path, SourceLocation{path, 0, 0}, fmt::format("deck file '{}'", path));
  return parseDeckText(text, path);
}

}  // namespace cc
