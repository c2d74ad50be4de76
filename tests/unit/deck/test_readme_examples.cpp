// The examples in input/README.md must be valid: every ```deck block parses, once completed with
// what a partial example leaves out (a mesh, an element block, a solve block). Mesh paths are
// replaced by a test fixture, since the parser checks that the mesh file exists.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "common/name_matching.hpp"
#include "deck_test_utils.hpp"

namespace cc::test {
namespace {

struct Example {
  int line = 0;  // of the opening fence in the README
  std::string text;
};

std::vector<Example> deckExamples() {
  std::ifstream stream(std::string(COVCONTACT_SOURCE_DIR) + "/input/README.md");
  std::vector<Example> examples;
  std::string line;
  bool inside = false;
  for (int number = 1; std::getline(stream, line); ++number) {
    if (!inside && line == "```deck") {
      inside = true;
      examples.push_back({number, ""});
    } else if (inside && line == "```") {
      inside = false;
    } else if (inside) {
      examples.back().text += line + "\n";
    }
  }
  return examples;
}

bool hasKeyword(const std::string& text, const std::string& keyword) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string first;
    if (words >> first && deck::equalsIgnoreCase(first, keyword)) return true;
  }
  return false;
}

std::string completed(const std::string& example) {
  static const std::regex meshPath(R"re((^|\n)(\s*mesh\s+)"[^"]*")re");
  std::string deck = std::regex_replace(example, meshPath, "$1$2\"meshes/two_blocks.geo\"");
  if (!hasKeyword(deck, "elements")) {
    deck =
        "material readme_material svk E=1 nu=0.3\n"
        "elements readme_group hex8 material=readme_material\n" +
        deck;
  }
  if (!hasKeyword(deck, "mesh")) deck = "mesh \"meshes/two_blocks.geo\"\n" + deck;
  if (!hasKeyword(deck, "solve")) deck += "solve\n  steps 1 dt=1\nend\n";
  return deck;
}

TEST(ReadmeExamples, EveryDeckExampleParses) {
  const std::vector<Example> examples = deckExamples();
  EXPECT_GE(examples.size(), 12u);
  for (const Example& example : examples) {
    SCOPED_TRACE("input/README.md example at line " + std::to_string(example.line));
    const std::string deck = completed(example.text);
    try {
      parseDeckText(deck, virtualDeckPath("readme.deck"));
    } catch (const InputError& error) {
      ADD_FAILURE() << error.what() << "\nin:\n" << deck;
    }
  }
}

}  // namespace
}  // namespace cc::test
