// Case-insensitive name lookup with unique-prefix abbreviations and edit-distance suggestions.
#include "common/name_matching.hpp"

#include <algorithm>
#include <cctype>

namespace cc::deck {

namespace {

// Typos the suggestion tolerates: one edit for short names, more for long ones.
int allowedDistance(std::size_t length) {
  constexpr std::size_t kShortName = 3;
  constexpr std::size_t kMediumName = 6;
  if (length <= kShortName) return 1;
  if (length <= kMediumName) return 2;
  return 3;
}

}  // namespace

std::string toLower(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower;
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  return toLower(a) == toLower(b);
}

NameMatch matchName(std::string_view word, const std::vector<std::string>& candidates) {
  NameMatch match;
  const std::string lowerWord = toLower(word);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (toLower(candidates[i]) == lowerWord) {
      match.index = static_cast<int>(i);
      return match;
    }
  }
  if (lowerWord.size() < kMinAbbreviationLength) return match;
  std::vector<int> prefixed;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (toLower(candidates[i]).starts_with(lowerWord)) prefixed.push_back(static_cast<int>(i));
  }
  if (prefixed.size() == 1) match.index = prefixed.front();
  if (prefixed.size() > 1) match.ambiguousWith = prefixed;
  return match;
}

int editDistance(std::string_view a, std::string_view b) {
  const std::string x = toLower(a);
  const std::string y = toLower(b);
  const std::size_t n = x.size();
  const std::size_t m = y.size();
  std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1, 0));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = static_cast<int>(i);
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= n; ++i) {
    for (std::size_t j = 1; j <= m; ++j) {
      const int substitution = x[i - 1] == y[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + substitution});
      if (i > 1 && j > 1 && x[i - 1] == y[j - 2] && x[i - 2] == y[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[n][m];
}

std::optional<std::string> suggestName(std::string_view word,
                                       const std::vector<std::string>& candidates) {
  const std::string lowerWord = toLower(word);
  if (lowerWord.empty()) return std::nullopt;
  std::vector<std::string> abbreviated;
  for (const std::string& candidate : candidates) {
    if (toLower(candidate).starts_with(lowerWord)) abbreviated.push_back(candidate);
  }
  if (abbreviated.size() == 1) return abbreviated.front();
  std::optional<std::string> best;
  int bestDistance = allowedDistance(lowerWord.size()) + 1;
  for (const std::string& candidate : candidates) {
    // The distance is at least the length difference: skip hopeless (e.g. huge) words.
    const auto lengthDifference =
        static_cast<int>(lowerWord.size() > candidate.size() ? lowerWord.size() - candidate.size()
                                                             : candidate.size() - lowerWord.size());
    if (lengthDifference >= bestDistance) continue;
    const int distance = editDistance(lowerWord, candidate);
    // Replacing every letter is no similarity (e.g. 'x' vs 'E').
    const auto longer = static_cast<int>(std::max(lowerWord.size(), candidate.size()));
    if (distance < bestDistance && distance < longer) {
      bestDistance = distance;
      best = candidate;
    }
  }
  return best;
}

std::string didYouMean(std::string_view word, const std::vector<std::string>& candidates) {
  const auto suggestion = suggestName(word, candidates);
  return suggestion ? "; did you mean '" + *suggestion + "'?" : std::string();
}

std::string joinAlternatives(const std::vector<std::string>& names) {
  std::string joined;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) joined += i + 1 == names.size() ? " or " : ", ";
    joined += names[i];
  }
  return joined;
}

}  // namespace cc::deck
