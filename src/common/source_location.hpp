// Where a piece of input came from (file, line, column), carried by every ProblemSpec item so that
// any later validation error can point the user at the exact place in the deck.
#pragma once

#include <string>

namespace cc {

struct SourceLocation {
  std::string file;  // path as the user gave it (or as resolved for includes)
  int line = 0;      // 1-based; 0 = unknown
  int column = 0;    // 1-based; 0 = unknown

  bool known() const { return !file.empty(); }
  // "file:line:column" (or "file:line", or "<unknown>"), the prefix of every input error message.
  std::string str() const;
};

}  // namespace cc
