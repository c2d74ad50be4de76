// Renders the keyword declarations as documentation: the Markdown reference pasted into
// input/README.md and the plain listing of `covcontact check --keywords`.
#include <fmt/format.h>

#include "common/name_matching.hpp"
#include "deck/deck_parser.hpp"
#include "deck/keyword_decl.hpp"

namespace cc {

namespace {

using deck::ClauseDecl;
using deck::KeywordDecl;
using deck::ValueDecl;

std::string blockName(KeywordDecl::Block block) {
  switch (block) {
    case KeywordDecl::Block::Model:
      return "model";
    case KeywordDecl::Block::Solve:
      return "solve block";
    case KeywordDecl::Block::Source:
      return "anywhere";
  }
  return "";
}

std::string tableCell(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    if (c == '|') escaped += '\\';
    escaped += c;
  }
  return escaped;
}

std::string defaultCell(const ValueDecl& value) {
  if (value.required) return "required";
  if (value.defaultText.empty()) return "optional";
  return fmt::format("`{}`", value.defaultText);
}

std::string clauseKind(ClauseDecl::Argument argument) {
  switch (argument) {
    case ClauseDecl::Argument::None:
      return "flag";
    case ClauseDecl::Argument::Function:
      return "function";
    case ClauseDecl::Argument::Identifier:
      return "name";
    case ClauseDecl::Argument::Points:
      return "points";
  }
  return "";
}

std::string markdownRow(const std::string& argument, const std::string& type,
                        const std::string& defaultText, const std::string& allowed,
                        const std::string& description) {
  return fmt::format("| {} | {} | {} | {} | {} |\n", tableCell(argument), tableCell(type),
                     tableCell(defaultText), tableCell(allowed), tableCell(description));
}

std::string markdownKeyword(const KeywordDecl& keyword) {
  std::string text = fmt::format("### `{}`\n\n{} Allowed in: {}.\n\n    {}\n\n", keyword.name,
                                 keyword.summary, blockName(keyword.block), keyword.synopsis());
  const bool hasItems = !keyword.positionals.empty() || !keyword.parameters.empty() ||
                        !keyword.clauses.empty() || !keyword.extraNumbers.empty();
  if (hasItems) {
    text += "| argument | type | default | allowed | description |\n";
    text += "|---|---|---|---|---|\n";
  }
  for (const ValueDecl& positional : keyword.positionals) {
    text += markdownRow(fmt::format("`{}`", positional.name), deck::typeDescription(positional),
                        "required", positional.range.describe(), positional.description);
  }
  for (const ValueDecl& parameter : keyword.parameters) {
    text += markdownRow(fmt::format("`{}=`", parameter.name), deck::typeDescription(parameter),
                        defaultCell(parameter), parameter.range.describe(), parameter.description);
  }
  for (const ClauseDecl& clause : keyword.clauses) {
    text += markdownRow(fmt::format("`{}`", deck::clauseSynopsis(clause)),
                        clauseKind(clause.argument), "optional", "", clause.description);
  }
  if (!keyword.extraNumbers.empty()) {
    text += markdownRow("`NAME=NUMBER`", "number", "optional", "", keyword.extraNumbers);
  }
  if (hasItems) text += "\n";
  if (!keyword.notes.empty()) text += keyword.notes + "\n\n";
  return text;
}

std::string listingValue(const ValueDecl& value, bool positional) {
  std::string facts = deck::typeDescription(value);
  const std::string range = value.range.describe();
  if (!range.empty()) facts += " " + range;
  if (value.required || positional) facts += ", required";
  if (!value.defaultText.empty()) facts += ", default " + value.defaultText;
  return fmt::format("    {:<16} {} ({})\n", positional ? value.name : value.name + "=",
                     value.description, facts);
}

}  // namespace

std::string keywordReferenceMarkdown() {
  std::string text = "| keyword | allowed in | summary |\n|---|---|---|\n";
  for (const KeywordDecl& keyword : deck::keywordTable()) {
    text += fmt::format("| [`{}`](#{}) | {} | {} |\n", keyword.name, keyword.name,
                        blockName(keyword.block), tableCell(keyword.summary));
  }
  text += "\n";
  for (const KeywordDecl& keyword : deck::keywordTable()) text += markdownKeyword(keyword);
  while (text.ends_with("\n\n")) text.pop_back();
  return text;
}

std::string keywordListing() {
  std::string text = fmt::format(
      "Deck keywords (case-insensitive; any unique prefix of at least {} letters works):\n",
      deck::kMinAbbreviationLength);
  for (const KeywordDecl& keyword : deck::keywordTable()) {
    text += fmt::format("\n{}\n  {} [{}]\n", keyword.synopsis(), keyword.summary,
                        blockName(keyword.block));
    for (const ValueDecl& positional : keyword.positionals) text += listingValue(positional, true);
    for (const ValueDecl& parameter : keyword.parameters) text += listingValue(parameter, false);
    for (const ClauseDecl& clause : keyword.clauses) {
      text += fmt::format("    {:<16} {}\n", deck::clauseSynopsis(clause), clause.description);
    }
    if (!keyword.extraNumbers.empty()) {
      text += fmt::format("    {:<16} {}\n", "NAME=NUMBER", keyword.extraNumbers);
    }
  }
  return text;
}

}  // namespace cc
