// The keyword declarations and their documentation: input/README.md holds exactly the generated
// reference, every declared default parses and lies in its range, and the listing is complete.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "common/name_matching.hpp"
#include "deck/keyword_decl.hpp"
#include "deck/parsed_line.hpp"
#include "deck_test_utils.hpp"
#include "fem/quadrature.hpp"

namespace cc::test {
namespace {

const std::string kBeginMarker = "<!-- keyword-reference:begin -->";
const std::string kEndMarker = "<!-- keyword-reference:end -->";

// Concatenation without GCC 12's false -Wrestrict positive on `"literal" + std::string`.
std::string concat(std::initializer_list<std::string_view> parts) {
  std::string text;
  for (std::string_view part : parts) text += part;
  return text;
}

std::string readmePath() {
  return std::string(COVCONTACT_SOURCE_DIR) + "/input/README.md";
}

TEST(KeywordReference, ReadmeSectionEqualsTheGeneratedReference) {
  std::ifstream stream(readmePath());
  ASSERT_TRUE(stream) << "cannot read " << readmePath();
  std::ostringstream contents;
  contents << stream.rdbuf();
  std::string readme = contents.str();
  const std::size_t begin = readme.find(kBeginMarker);
  const std::size_t end = readme.find(kEndMarker);
  ASSERT_NE(begin, std::string::npos) << "missing " << kBeginMarker;
  ASSERT_NE(end, std::string::npos) << "missing " << kEndMarker;
  ASSERT_LT(begin, end);
  const std::size_t sectionStart = begin + kBeginMarker.size();
  const std::string generated = concat({"\n", keywordReferenceMarkdown(), "\n"});
  // Regenerate with: COVCONTACT_UPDATE_README=1 test_deck --gtest_filter=KeywordReference.*
  if (const char* update = std::getenv("COVCONTACT_UPDATE_README"); update && *update == '1') {
    readme.replace(sectionStart, end - sectionStart, generated);
    std::ofstream(readmePath(), std::ios::binary) << readme;
    return;
  }
  EXPECT_EQ(readme.substr(sectionStart, end - sectionStart), generated)
      << "input/README.md is out of date; regenerate it with COVCONTACT_UPDATE_README=1 "
         "test_deck --gtest_filter=KeywordReference.*";
}

// A value of the declared type inside the declared range, in deck syntax.
std::string sampleValue(const deck::ValueDecl& value) {
  const double bound = value.range.lower.value_or(0.0);
  switch (value.type) {
    case deck::ValueType::Number:
      return std::to_string(bound + 0.25);
    case deck::ValueType::Integer:
      return std::to_string(static_cast<long long>(bound) + 1);
    case deck::ValueType::String:
      return "\"sample\"";
    case deck::ValueType::Identifier:
      return "sample";
    case deck::ValueType::Enum:
    case deck::ValueType::EnumList:
      return value.choices.front();
    case deck::ValueType::Vector:
      return "(1,0,0)";
    case deck::ValueType::Bool:
      return "yes";
  }
  return "";
}

// Parses "KEYWORD <positionals> <required parameters>" so that every other parameter takes its
// declared default: a default that does not parse or lies outside its range throws.
TEST(KeywordReference, EveryDefaultParsesAndLiesInItsRange) {
  int defaultsChecked = 0;
  for (const deck::KeywordDecl& keyword : deck::keywordTable()) {
    std::string text = keyword.name;
    for (const deck::ValueDecl& positional : keyword.positionals) {
      text += concat({" ", sampleValue(positional)});
    }
    for (const deck::ValueDecl& parameter : keyword.parameters) {
      if (parameter.required) text += concat({" ", parameter.name, "=", sampleValue(parameter)});
    }
    SCOPED_TRACE(text);
    const std::vector<deck::LogicalLine> lines = deck::tokenize(text, "declarations");
    ASSERT_EQ(lines.size(), 1u);
    const deck::ParsedLine line(lines.front(), keyword);
    for (const deck::ValueDecl& parameter : keyword.parameters) {
      if (parameter.defaultText.empty()) continue;
      EXPECT_FALSE(parameter.required) << parameter.name << ": required with a default";
      EXPECT_FALSE(line.given(parameter.name));
      EXPECT_EQ(line.value(parameter.name).raw, parameter.defaultText);
      ++defaultsChecked;
    }
  }
  EXPECT_GE(defaultsChecked, 20);
}

TEST(KeywordReference, NamesAreUniqueAndKeywordsAbbreviateToFourLetters) {
  const std::vector<std::string> keywords = deck::keywordNames();
  for (std::size_t i = 0; i < keywords.size(); ++i) {
    const std::string prefix = keywords[i].substr(0, deck::kMinAbbreviationLength);
    const deck::NameMatch match = deck::matchName(prefix, keywords);
    EXPECT_EQ(match.index, static_cast<int>(i)) << keywords[i];
  }
  for (const deck::KeywordDecl& keyword : deck::keywordTable()) {
    std::vector<std::string> words = keyword.parameterNames();
    for (const std::string& clause : keyword.clauseNames()) words.push_back(clause);
    for (std::size_t i = 0; i < words.size(); ++i) {
      for (std::size_t j = i + 1; j < words.size(); ++j) {
        EXPECT_FALSE(deck::equalsIgnoreCase(words[i], words[j]))
            << keyword.name << ": " << words[i] << " declared twice";
      }
    }
    EXPECT_FALSE(keyword.summary.empty()) << keyword.name;
    EXPECT_TRUE(keyword.handler != nullptr || keyword.block == deck::KeywordDecl::Block::Source)
        << keyword.name;
  }
}

TEST(KeywordReference, ListingAndMarkdownNameEveryKeywordAndParameter) {
  const std::string listing = keywordListing();
  const std::string markdown = keywordReferenceMarkdown();
  for (const deck::KeywordDecl& keyword : deck::keywordTable()) {
    EXPECT_NE(listing.find(concat({"\n", keyword.synopsis(), "\n"})), std::string::npos)
        << keyword.name;
    EXPECT_NE(markdown.find(concat({"### `", keyword.name, "`"})), std::string::npos)
        << keyword.name;
    EXPECT_NE(markdown.find(concat({"    ", keyword.synopsis(), "\n"})), std::string::npos);
    for (const deck::ValueDecl& parameter : keyword.parameters) {
      EXPECT_NE(listing.find(concat({"    ", parameter.name, "="})), std::string::npos)
          << keyword.name << " " << parameter.name;
      EXPECT_NE(markdown.find(concat({"| `", parameter.name, "=` |"})), std::string::npos)
          << keyword.name << " " << parameter.name;
    }
  }
}

// The contact `points=` range must match the quadrature rules the contact code can use.
TEST(KeywordReference, ContactPointsRangeMatchesTheQuadratureRules) {
  for (const deck::KeywordDecl& keyword : deck::keywordTable()) {
    if (keyword.name != "contact") continue;
    const deck::ValueDecl* points = keyword.findParameter("points");
    ASSERT_NE(points, nullptr);
    EXPECT_EQ(points->range.lower, 1.0);
    EXPECT_EQ(points->range.upper, static_cast<double>(kMaxGaussPoints));
    EXPECT_TRUE(points->range.contains(kMaxGaussPoints));
    EXPECT_FALSE(points->range.contains(kMaxGaussPoints + 1));
  }
}

TEST(KeywordReference, SynopsisShowsRequiredAndOptionalItems) {
  for (const deck::KeywordDecl& keyword : deck::keywordTable()) {
    if (keyword.name == "material") {
      EXPECT_EQ(keyword.synopsis(),
                "material NAME svk|neohooke|neohooke_decoupled E=NUMBER nu=NUMBER");
    }
    if (keyword.name == "fix") {
      EXPECT_EQ(keyword.synopsis(), "fix SET [ux] [uy] [uz] [all]");
    }
    if (keyword.name == "mesh") {
      EXPECT_EQ(keyword.synopsis(), "mesh PATH [NAME=NUMBER ...]");
    }
  }
}

}  // namespace
}  // namespace cc::test
