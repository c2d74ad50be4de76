// Declarations of the deck keywords: each keyword is declared once with its positional
// arguments, its NAME=VALUE parameters (type, default, allowed range, description) and its
// clauses. The declarations drive parsing, validation, `check --keywords` and input/README.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace cc::deck {

enum class ValueType {
  Number,      // any C floating-point notation, finite
  Integer,     // decimal digits with an optional sign
  String,      // "quoted text" (or a single word)
  Identifier,  // a name: letters, digits, '_', '-', '.', ':' (or quoted)
  Enum,        // one of `choices`
  EnumList,    // comma-separated choices: a,b,c
  Vector,      // (x,y,z)
  Bool,        // yes/no (also true/false)
};

// Allowed interval of a Number or Integer; either bound may be open, closed or absent.
struct Range {
  std::optional<double> lower;
  std::optional<double> upper;
  bool lowerInclusive = true;
  bool upperInclusive = true;

  static Range any() { return {}; }
  static Range greaterThan(double bound) { return {bound, std::nullopt, false, true}; }
  static Range atLeast(double bound) { return {bound, std::nullopt, true, true}; }
  static Range between(double lowerBound, bool lowerClosed, double upperBound, bool upperClosed) {
    return {lowerBound, upperBound, lowerClosed, upperClosed};
  }

  bool contains(double value) const;
  bool restricted() const { return lower || upper; }
  std::string describe() const;  // "> 0", ">= 1", "> -1 and < 0.5", "" if unrestricted
};

// A positional argument or a NAME=VALUE parameter.
struct ValueDecl {
  std::string name;  // parameters: as written before '='; positionals: an upper-case placeholder
  ValueType type = ValueType::Number;
  std::vector<std::string> choices;  // Enum, EnumList
  Range range;
  std::string defaultText;  // deck syntax of the default; empty = no default
  bool required = false;
  std::string description;  // one line
  // A node SET positional: its word may be the built-in set `all` (kAllNodesSet) even where
  // `all` is also a clause of the keyword (`fix all uz`).
  bool nodeSet = false;

  ValueDecl withRange(Range allowed) const;
  ValueDecl withDefault(std::string text) const;
  ValueDecl asRequired() const;
  ValueDecl renamed(std::string newName) const;
};

ValueDecl numberValue(std::string name, std::string description);
ValueDecl integerValue(std::string name, std::string description);
ValueDecl stringValue(std::string name, std::string description);
ValueDecl identifierValue(std::string name, std::string description);
// The SET of fix, prescribe and load: a physical group's nodes or the built-in set `all`.
ValueDecl nodeSetValue(std::string name, std::string description);
ValueDecl enumValue(std::string name, std::vector<std::string> choices, std::string description);
ValueDecl enumListValue(std::string name, std::vector<std::string> choices,
                        std::string description);
ValueDecl vectorValue(std::string name, std::string description);
ValueDecl boolValue(std::string name, std::string description);

// "number", "integer", "svk | neohooke", "list of a, b", "vector (x,y,z)", "yes | no", ...
std::string typeDescription(const ValueDecl& value);

// A word after the positional arguments that may be followed by its own argument, e.g.
// `ux "0.1*t"`, `table (0,0) (1,2)`, `total`.
struct ClauseDecl {
  enum class Argument {
    None,        // a flag word
    Function,    // "expression" | number | table (t,v) (t,v) ...
    Identifier,  // a name
    Points,      // (t,v) (t,v) ... with t strictly increasing
  };
  std::string name;
  Argument argument = Argument::None;
  std::string description;
};

std::string clauseSynopsis(const ClauseDecl& clause);  // `ux FUNCTION`, `total`, ...

class ParsedLine;
struct DeckState;
using KeywordHandler = void (*)(const ParsedLine& line, DeckState& state);

struct KeywordDecl {
  enum class Block { Model, Solve, Source };  // Source: handled while reading files (include)
  std::string name{};
  Block block = Block::Model;
  std::string summary{};  // one line
  std::vector<ValueDecl> positionals{};
  std::vector<ValueDecl> parameters{};
  std::vector<ClauseDecl> clauses{};
  // Non-empty: NAME=NUMBER pairs other than the declared parameters are accepted (gmsh
  // variables, analytic-solution parameters); this text documents them.
  std::string extraNumbers{};
  // Positional (by placeholder) or parameter whose value names the item in error messages.
  std::string itemName{};
  std::string notes{};  // extra paragraph for the reference (semantics, interplay of parameters)
  KeywordHandler handler = nullptr;

  std::string synopsis() const;  // `material NAME MODEL E=NUMBER nu=NUMBER`
  const ValueDecl* findParameter(const std::string& canonicalName) const;
  std::vector<std::string> parameterNames() const;
  std::vector<std::string> clauseNames() const;
};

// Every keyword, in the order of the reference documentation.
const std::vector<KeywordDecl>& keywordTable();
std::vector<std::string> keywordNames();

}  // namespace cc::deck
