// The bad-deck corpus (tests/decks/bad/*.deck) at parser level: every deck not marked
// `# needs: mesh` must be rejected by parseDeck with a message containing its
// `# expect-message:` fragment. (The same decks run through `covcontact check` in CTest.)
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "deck_test_utils.hpp"

namespace cc::test {
namespace {

namespace fs = std::filesystem;

struct BadDeck {
  fs::path path;
  int expectedExit = -1;
  std::string expectedMessage;
  bool needsMesh = false;
};

// Reads the leading comment lines "# expect-exit: N", "# expect-message: ...", "# needs: mesh".
BadDeck readHeader(const fs::path& path) {
  BadDeck deck;
  deck.path = path;
  std::ifstream stream(path);
  std::string line;
  while (std::getline(stream, line) && line.starts_with("#")) {
    auto valueAfter = [&](const std::string& key) -> std::optional<std::string> {
      if (!line.starts_with(key)) return std::nullopt;
      std::string value = line.substr(key.size());
      value.erase(0, value.find_first_not_of(' '));
      while (!value.empty() && (value.back() == ' ' || value.back() == '\r')) value.pop_back();
      return value;
    };
    if (auto exit = valueAfter("# expect-exit:")) deck.expectedExit = std::stoi(*exit);
    if (auto message = valueAfter("# expect-message:")) deck.expectedMessage = *message;
    if (auto needs = valueAfter("# needs:")) deck.needsMesh = *needs == "mesh";
  }
  return deck;
}

std::vector<BadDeck> badDecks() {
  std::vector<BadDeck> decks;
  for (const auto& entry :
       fs::directory_iterator(fs::path(COVCONTACT_SOURCE_DIR) / "tests/decks/bad")) {
    if (entry.path().extension() == ".deck") decks.push_back(readHeader(entry.path()));
  }
  std::sort(decks.begin(), decks.end(),
            [](const BadDeck& a, const BadDeck& b) { return a.path < b.path; });
  return decks;
}

TEST(BadDecks, CorpusIsLargeAndEveryDeckDeclaresItsExpectation) {
  const std::vector<BadDeck> decks = badDecks();
  EXPECT_GE(decks.size(), 45u);
  for (const BadDeck& deck : decks) {
    SCOPED_TRACE(deck.path.string());
    EXPECT_GT(deck.expectedExit, 0);
    EXPECT_FALSE(deck.expectedMessage.empty());
  }
}

TEST(BadDecks, ParserRejectsEveryParserLevelDeckWithItsMessage) {
  int checked = 0;
  for (const BadDeck& deck : badDecks()) {
    if (deck.needsMesh) continue;
    SCOPED_TRACE(deck.path.string());
    EXPECT_EQ(deck.expectedExit, kExitInput);
    try {
      parseDeck(deck.path.string());
      ADD_FAILURE() << "parsed without error";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(deck.expectedMessage), std::string::npos)
          << "message: " << error.what() << "\nexpected fragment: " << deck.expectedMessage;
    }
    ++checked;
  }
  EXPECT_GE(checked, 45);
}

// Decks marked `# needs: mesh` are valid as far as the parser can tell: their problem shows
// only against the mesh (or its expressions), so the parser must accept them.
TEST(BadDecks, MeshLevelDecksPassTheParser) {
  for (const BadDeck& deck : badDecks()) {
    if (!deck.needsMesh) continue;
    SCOPED_TRACE(deck.path.string());
    EXPECT_NO_THROW(parseDeck(deck.path.string()));
  }
}

}  // namespace
}  // namespace cc::test
