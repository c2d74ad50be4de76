// Includes: nested resolution relative to the including file, the combined deck text, errors
// located in included files, missing files and include cycles.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "deck_test_utils.hpp"

namespace cc::test {
namespace {

namespace fs = std::filesystem;

std::string readFile(const std::string& path) {
  std::ifstream stream(path);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

std::string normal(const std::string& path) {
  return fs::path(path).lexically_normal();
}

TEST(DeckIncludes, NestedIncludesResolveRelativeToTheIncludingFile) {
  const std::string mainPath = unitDataPath("include_main.deck");
  const ProblemSpec spec = parseDeck(mainPath);
  ASSERT_EQ(spec.materials.size(), 2u);
  EXPECT_EQ(spec.materials[0].name, "steel");
  EXPECT_EQ(spec.materials[1].name, "rubber");
  EXPECT_EQ(spec.materials[1].where.file, normal(unitDataPath("include/nested.inc")));
  EXPECT_EQ(spec.materials[1].where.line, 1);
  ASSERT_EQ(spec.phases.size(), 1u);  // the include inside the solve block
  EXPECT_EQ(spec.phases[0].steps, 2);
  EXPECT_EQ(spec.phases[0].newton.maxIterations, 7);
  EXPECT_EQ(spec.mesh.path,
            normal(std::string(COVCONTACT_SOURCE_DIR) + "/tests/decks/meshes/cube.geo"));
  EXPECT_EQ(spec.deckPath, mainPath);
}

TEST(DeckIncludes, DeckTextIsTheMainTextFollowedByEachIncludedFile) {
  const std::string mainPath = unitDataPath("include_main.deck");
  const ProblemSpec spec = parseDeck(mainPath);
  std::string expected = readFile(mainPath);
  for (const char* name : {"include/materials.inc", "include/nested.inc", "include/phases.inc"}) {
    expected += "\n# ---- included file: " + normal(unitDataPath(name)) + " ----\n";
    expected += readFile(unitDataPath(name));
  }
  EXPECT_EQ(spec.deckText, expected);
}

TEST(DeckIncludes, ErrorsInAnIncludedFileNameThatFile) {
  const InputError error = parseError(
      kMinimalDeck + "include \"../unit/deck/data/include/bad_value.inc\"\n", virtualDeckPath());
  EXPECT_EQ(error.where().file, normal(unitDataPath("include/bad_value.inc")));
  EXPECT_EQ(error.where().line, 2);
  EXPECT_EQ(error.where().column, 33);
  EXPECT_EQ(error.bareMessage(), "material 'rubber': nu must be > -1 and < 0.5, got 0.5");
}

TEST(DeckIncludes, MissingIncludeNamesTheIncludingLine) {
  const InputError error =
      parseError(kMinimalDeck + "include \"include/no_such_file.inc\"\n", virtualDeckPath());
  EXPECT_EQ(error.where().file, virtualDeckPath());
  EXPECT_EQ(error.where().line, 8);
  EXPECT_EQ(error.where().column, 9);
  const std::string looked = normal(virtualDeckPath("include/no_such_file.inc"));
  EXPECT_EQ(error.bareMessage(),
            "cannot open include file 'include/no_such_file.inc' (looked "
            "for '" +
                looked + "')");
}

TEST(DeckIncludes, CycleIsAnErrorNamingTheCycle) {
  const InputError error =
      parseError(kMinimalDeck + "include \"cycle/first.inc\"\n", unitDataPath("virtual.deck"));
  const std::string first = normal(unitDataPath("cycle/first.inc"));
  const std::string second = normal(unitDataPath("cycle/second.inc"));
  EXPECT_EQ(error.where().file, second);
  EXPECT_EQ(error.where().line, 2);
  EXPECT_EQ(error.bareMessage(), "include cycle: " + first + " -> " + second + " -> " + first);
}

TEST(DeckIncludes, IncludingTheDeckItselfIsACycle) {
  const std::string path = unitDataPath("virtual.deck");
  const InputError error = parseError("include \"virtual.deck\"\n", path);
  EXPECT_EQ(error.bareMessage(), "include cycle: " + path + " -> " + path);
}

TEST(DeckIncludes, MissingDeckFile) {
  const std::string path = unitDataPath("no_such.deck");
  try {
    parseDeck(path);
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), path + ": error: cannot open deck file '" + path + "'");
  }
}

}  // namespace
}  // namespace cc::test

namespace cc::test {
namespace {

// Writes a chain main.deck -> 1.inc -> 2.inc -> ... -> depth.inc in a fresh directory.
std::string writeIncludeChain(const std::string& name, int depth) {
  const fs::path directory = fs::path(COVCONTACT_BINARY_DIR) / "tests" / "scratch" / name;
  fs::remove_all(directory);
  fs::create_directories(directory);
  for (int level = 1; level <= depth; ++level) {
    std::ofstream(directory / (std::to_string(level) + ".inc"))
        << (level < depth ? "include \"" + std::to_string(level + 1) + ".inc\"\n"
                          : "# the end of the chain\n");
  }
  const fs::path main = directory / "main.deck";
  std::string deck = kMinimalDeck;
  deck.replace(deck.find("meshes/"), 7,
               std::string(COVCONTACT_SOURCE_DIR) + "/tests/decks/meshes/");
  std::ofstream(main) << "include \"1.inc\"\n" << deck;
  return main.string();
}

// The expansion recurses once per level: a chain thousands deep overflowed the stack (SIGSEGV).
TEST(DeckIncludes, AnIncludeChainDeeperThanTheLimitIsRefusedWithAMessage) {
  const std::string deep = writeIncludeChain("include_chain_deep", 5000);
  try {
    parseDeck(deep);
    FAIL() << "a 5000-deep include chain was accepted";
  } catch (const InputError& error) {
    EXPECT_NE(error.bareMessage().find("includes nested more than 64 deep"), std::string::npos)
        << error.what();
    EXPECT_EQ(error.where().file, normal(fs::path(deep).parent_path() / "63.inc"));
    EXPECT_EQ(error.where().line, 1);
  }
  // The main deck and 63 nested includes (64 open files) still parse.
  const ProblemSpec spec = parseDeck(writeIncludeChain("include_chain_at_limit", 63));
  EXPECT_EQ(spec.deckFiles.size(), 64u);
}

}  // namespace
}  // namespace cc::test
