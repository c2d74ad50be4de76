// One deck line interpreted against its keyword declaration: typed positional arguments,
// parameters (given or defaulted), clauses and extra NAME=NUMBER pairs, all range-checked and
// located. Keyword handlers read values from here and never see tokens.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "deck/deck_lexer.hpp"
#include "deck/keyword_decl.hpp"
#include "spec/problem_spec.hpp"

namespace cc::deck {

struct Value {
  const ValueDecl* decl = nullptr;
  bool given = false;  // false: the declared default
  std::string raw;     // as written, for messages
  double number = 0;
  long long integer = 0;
  std::string text;               // String, Identifier, Enum (the declared spelling)
  std::vector<std::string> list;  // EnumList (declared spellings)
  Vec3 vector{0, 0, 0};
  bool flag = false;
  SourceLocation where;
};

struct Clause {
  const ClauseDecl* decl = nullptr;
  SourceLocation where;                  // the clause word
  std::optional<FunctionSpec> function;  // Argument::Function
  std::string identifier;                // Argument::Identifier
  SourceLocation identifierWhere;
  std::vector<std::pair<double, double>> points;  // Argument::Points
};

struct ExtraNumber {
  std::string name;  // as written (case kept: gmsh variables are case-sensitive)
  double value = 0;
  SourceLocation where;
};

class ParsedLine {
 public:
  // Throws InputError naming the file:line:column of the offending token.
  ParsedLine(const LogicalLine& line, const KeywordDecl& keyword);

  const KeywordDecl& keyword() const { return *keyword_; }
  const SourceLocation& where() const { return where_; }
  const SourceLocation& end() const { return end_; }
  // "material 'soft'" or "steps": the prefix of every message about this line.
  const std::string& context() const { return context_; }

  const Value& positional(std::size_t index) const { return positionals_.at(index); }
  bool given(const std::string& parameter) const;
  // The given value or the declared default; throws std::logic_error if there is neither
  // (handlers test given() first for optional parameters without a default).
  const Value& value(const std::string& parameter) const;
  double number(const std::string& parameter) const { return value(parameter).number; }
  int integer(const std::string& parameter) const;
  const std::string& text(const std::string& parameter) const { return value(parameter).text; }
  bool flag(const std::string& parameter) const { return value(parameter).flag; }

  const std::vector<Clause>& clauses() const { return clauses_; }
  const Clause* findClause(const std::string& name) const;
  const std::vector<ExtraNumber>& extraNumbers() const { return extraNumbers_; }

  [[noreturn]] void fail(const SourceLocation& where, const std::string& message) const;

 private:
  friend class LineReader;
  const KeywordDecl* keyword_;
  SourceLocation where_;
  SourceLocation end_;
  std::string context_;
  std::vector<Value> positionals_;
  std::map<std::string, Value> parameters_;  // by declared name; defaults included
  std::vector<Clause> clauses_;
  std::vector<ExtraNumber> extraNumbers_;
};

// Number syntax shared with tests: C notation via strtod, finite, nothing trailing.
// Returns an error text ("" on success).
std::string parseNumberText(const std::string& text, double& number);
std::string parseIntegerText(const std::string& text, long long& integer);

}  // namespace cc::deck
