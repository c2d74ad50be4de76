// Reading deck files: the main deck and its (nested) includes, flattened into one sequence of
// logical lines, with cycle detection and the combined text stored in the results.
#pragma once

#include <string>
#include <vector>

#include "deck/deck_lexer.hpp"

namespace cc::deck {

struct DeckSource {
  std::vector<LogicalLine> lines;  // include lines replaced by the included files' lines
  std::string text;  // the main text, then each included file once, after a "# ---" line
  std::vector<std::string> files;  // the main deck and every included file, each once
};

// Deepest include nesting accepted: deeper chains are refused with a message instead of
// exhausting the stack (the expansion recurses once per level).
inline constexpr std::size_t kMaxIncludeDepth = 64;

// Reads a whole file; throws InputError at `requestedAt` (naming `what`) if it cannot.
std::string readDeckFile(const std::string& path, const SourceLocation& requestedAt,
                         const std::string& what);

// `path` locates `text` (for messages and for resolving includes relative to its directory).
DeckSource loadDeckSource(const std::string& text, const std::string& path);

}  // namespace cc::deck
