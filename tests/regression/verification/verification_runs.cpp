// Test support: verification decks with changes, run in-process, with their reference errors.
#include "verification_runs.hpp"

#include <fmt/format.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace cc::test {

namespace {

std::string readFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::invalid_argument("cannot read " + path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Multiplies the number after `key=` on every line that starts with `contact`.
std::string scalePenalty(const std::string& text, const std::string& key, double factor) {
  const std::regex contactLine("^contact .*$", std::regex::multiline);
  const std::regex value("\\b" + key + "=([^ \\n]+)");
  std::string result;
  auto begin = std::sregex_iterator(text.begin(), text.end(), contactLine);
  std::size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    std::string line = it->str();
    std::smatch match;
    if (std::regex_search(line, match, value)) {
      line.replace(match.position(1), match.length(1),
                   fmt::format("{:.6g}", std::stod(match[1]) * factor));
    }
    result += text.substr(last, it->position() - last) + line;
    last = it->position() + it->length();
  }
  return result + text.substr(last);
}

}  // namespace

std::string changedDeck(const std::string& deckPath, const DeckChanges& changes) {
  std::string text = readFile(deckPath);
  const std::size_t meshStart = text.find("\nmesh ") + 1;
  const std::size_t meshEnd = text.find('\n', meshStart);
  std::string meshLine = text.substr(meshStart, meshEnd - meshStart);
  for (const auto& [name, value] : changes.mesh) {
    const std::regex parameter("\\b" + name + "=[^ ]+");
    if (!std::regex_search(meshLine, parameter)) {
      throw std::invalid_argument(deckPath + ": no mesh parameter " + name);
    }
    meshLine = std::regex_replace(meshLine, parameter, name + "=" + value);
  }
  text.replace(meshStart, meshEnd - meshStart, meshLine);
  if (changes.penaltyScale != 1) {
    text = scalePenalty(scalePenalty(text, "eps_n", changes.penaltyScale), "eps_t",
                        changes.penaltyScale);
  }
  for (const auto& [from, to] : changes.replace) {
    std::size_t at = text.find(from);
    if (at == std::string::npos) throw std::invalid_argument(deckPath + ": no text '" + from + "'");
    for (; at != std::string::npos; at = text.find(from, at + to.size()))
      text.replace(at, from.size(), to);
  }
  return text;
}

const verification::ReferenceResult& VerifiedRun::operator[](const std::string& quantity) const {
  const auto found = errors.find(quantity);
  if (found == errors.end()) throw std::out_of_range("no reference for " + quantity);
  return found->second;
}

VerifiedRun runVerificationDeck(const std::string& deckPath, const DeckChanges& changes) {
  VerifiedRun verified;
  verified.run = runDeckText(changedDeck(deckPath, changes), deckPath);
  verification::ReferenceTracker tracker(*verified.run.model);
  for (const RecordedStep& step : verified.run.steps) tracker.observe(step.record());
  for (verification::ReferenceResult& result : tracker.results()) {
    verified.errors.emplace(result.quantity, std::move(result));
  }
  return verified;
}

}  // namespace cc::test
