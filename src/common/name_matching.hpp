// Name matching for deck words: case-insensitive lookup with FEAP-style abbreviations (a unique
// prefix of at least four letters) and "did you mean" suggestions by edit distance.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cc::deck {

// FEAP accepts the first four letters of a command; we accept any longer unique prefix as well.
inline constexpr std::size_t kMinAbbreviationLength = 4;

std::string toLower(std::string_view text);
bool equalsIgnoreCase(std::string_view a, std::string_view b);

struct NameMatch {
  int index = -1;                  // the matched name, or -1
  std::vector<int> ambiguousWith;  // candidates sharing the given prefix when it is not unique
  bool found() const { return index >= 0; }
};

// Exact (case-insensitive) match first; otherwise a prefix of >= kMinAbbreviationLength letters
// that starts exactly one candidate.
NameMatch matchName(std::string_view word, const std::vector<std::string>& candidates);

// Restricted Damerau-Levenshtein distance (insertions, deletions, substitutions, transpositions
// of neighbours), case-insensitive.
int editDistance(std::string_view a, std::string_view b);

// The candidate the user most likely meant: a candidate that the word abbreviates too briefly,
// or the closest one within an edit distance that grows with the word's length.
std::optional<std::string> suggestName(std::string_view word,
                                       const std::vector<std::string>& candidates);

// "; did you mean 'X'?" or "" when nothing is close enough.
std::string didYouMean(std::string_view word, const std::vector<std::string>& candidates);

// "a, b or c"
std::string joinAlternatives(const std::vector<std::string>& names);

}  // namespace cc::deck
