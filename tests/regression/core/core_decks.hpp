// Shared helpers of the issue-2 whole-program tests: paths and text of the verification decks in
// input/verification/core, and deck variants with one model line replaced (a refinement level,
// another material), run in-process with tests/support/deck_runner.hpp.
#pragma once

#include <string>

namespace cc::test {

// Absolute path of input/verification/core/<name>.
std::string coreDeckPath(const std::string& name);

// The whole file; throws std::runtime_error if it cannot be read.
std::string readText(const std::string& path);

// `text` with its single line that starts with `keyword` (followed by a blank) replaced by
// `line`; throws std::invalid_argument unless exactly one line matches, so a variant can never
// silently run the unmodified deck.
std::string replaceLine(const std::string& text, const std::string& keyword,
                        const std::string& line);

}  // namespace cc::test
