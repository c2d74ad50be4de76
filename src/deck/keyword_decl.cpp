// Keyword declaration helpers: value constructors, ranges, and the synopsis text they render.
#include "deck/keyword_decl.hpp"

#include <fmt/format.h>

namespace cc::deck {

bool Range::contains(double value) const {
  if (lower && (lowerInclusive ? value < *lower : value <= *lower)) return false;
  if (upper && (upperInclusive ? value > *upper : value >= *upper)) return false;
  return true;
}

std::string Range::describe() const {
  std::string lowerText;
  std::string upperText;
  if (lower) lowerText = fmt::format("{} {}", lowerInclusive ? ">=" : ">", *lower);
  if (upper) upperText = fmt::format("{} {}", upperInclusive ? "<=" : "<", *upper);
  if (lower && upper) return lowerText + " and " + upperText;
  return lower ? lowerText : upperText;
}

ValueDecl ValueDecl::withRange(Range allowed) const {
  ValueDecl copy = *this;
  copy.range = allowed;
  return copy;
}

ValueDecl ValueDecl::withDefault(std::string text) const {
  ValueDecl copy = *this;
  copy.defaultText = std::move(text);
  return copy;
}

ValueDecl ValueDecl::asRequired() const {
  ValueDecl copy = *this;
  copy.required = true;
  return copy;
}

ValueDecl ValueDecl::renamed(std::string newName) const {
  ValueDecl copy = *this;
  copy.name = std::move(newName);
  return copy;
}

namespace {

ValueDecl makeValue(std::string name, ValueType type, std::string description,
                    std::vector<std::string> choices = {}) {
  ValueDecl value;
  value.name = std::move(name);
  value.type = type;
  value.description = std::move(description);
  value.choices = std::move(choices);
  return value;
}

std::string joinChoices(const std::vector<std::string>& choices, const char* separator) {
  std::string joined;
  for (const std::string& choice : choices) {
    if (!joined.empty()) joined += separator;
    joined += choice;
  }
  return joined;
}

// What goes after NAME= in a synopsis.
std::string valuePlaceholder(const ValueDecl& value) {
  switch (value.type) {
    case ValueType::Number:
      return "NUMBER";
    case ValueType::Integer:
      return "INTEGER";
    case ValueType::String:
      return "\"TEXT\"";
    case ValueType::Identifier:
      return "NAME";
    case ValueType::Enum:
      return joinChoices(value.choices, "|");
    case ValueType::EnumList:
      return "LIST";
    case ValueType::Vector:
      return "(X,Y,Z)";
    case ValueType::Bool:
      return "yes|no";
  }
  return "VALUE";
}

}  // namespace

ValueDecl numberValue(std::string name, std::string description) {
  return makeValue(std::move(name), ValueType::Number, std::move(description));
}
ValueDecl integerValue(std::string name, std::string description) {
  return makeValue(std::move(name), ValueType::Integer, std::move(description));
}
ValueDecl stringValue(std::string name, std::string description) {
  return makeValue(std::move(name), ValueType::String, std::move(description));
}
ValueDecl identifierValue(std::string name, std::string description) {
  return makeValue(std::move(name), ValueType::Identifier, std::move(description));
}
ValueDecl nodeSetValue(std::string name, std::string description) {
  ValueDecl value = identifierValue(std::move(name), std::move(description));
  value.nodeSet = true;
  return value;
}
ValueDecl enumValue(std::string name, std::vector<std::string> choices, std::string description) {
  return makeValue(std::move(name), ValueType::Enum, std::move(description), std::move(choices));
}
ValueDecl enumListValue(std::string name, std::vector<std::string> choices,
                        std::string description) {
  return makeValue(std::move(name), ValueType::EnumList, std::move(description),
                   std::move(choices));
}
ValueDecl vectorValue(std::string name, std::string description) {
  return makeValue(std::move(name), ValueType::Vector, std::move(description));
}
ValueDecl boolValue(std::string name, std::string description) {
  return makeValue(std::move(name), ValueType::Bool, std::move(description));
}

std::string typeDescription(const ValueDecl& value) {
  switch (value.type) {
    case ValueType::Number:
      return "number";
    case ValueType::Integer:
      return "integer";
    case ValueType::String:
      return "string";
    case ValueType::Identifier:
      return "name";
    case ValueType::Enum:
      return joinChoices(value.choices, " | ");
    case ValueType::EnumList:
      return "list of " + joinChoices(value.choices, ", ");
    case ValueType::Vector:
      return "vector (x,y,z)";
    case ValueType::Bool:
      return "yes | no";
  }
  return "value";
}

std::string clauseSynopsis(const ClauseDecl& clause) {
  switch (clause.argument) {
    case ClauseDecl::Argument::None:
      return clause.name;
    case ClauseDecl::Argument::Function:
      return clause.name + " FUNCTION";
    case ClauseDecl::Argument::Identifier:
      return clause.name + " NAME";
    case ClauseDecl::Argument::Points:
      return clause.name + " (T,V) (T,V) ...";
  }
  return clause.name;
}

std::string KeywordDecl::synopsis() const {
  std::string text = name;
  for (const ValueDecl& positional : positionals) {
    text += " " + (positional.type == ValueType::Enum ? joinChoices(positional.choices, "|")
                                                      : positional.name);
  }
  for (const ValueDecl& parameter : parameters) {
    const std::string item = parameter.name + "=" + valuePlaceholder(parameter);
    text += parameter.required ? " " + item : " [" + item + "]";
  }
  for (const ClauseDecl& clause : clauses) text += " [" + clauseSynopsis(clause) + "]";
  if (!extraNumbers.empty()) text += " [NAME=NUMBER ...]";
  return text;
}

const ValueDecl* KeywordDecl::findParameter(const std::string& canonicalName) const {
  for (const ValueDecl& parameter : parameters) {
    if (parameter.name == canonicalName) return &parameter;
  }
  return nullptr;
}

std::vector<std::string> KeywordDecl::parameterNames() const {
  std::vector<std::string> names;
  for (const ValueDecl& parameter : parameters) names.push_back(parameter.name);
  return names;
}

std::vector<std::string> KeywordDecl::clauseNames() const {
  std::vector<std::string> names;
  for (const ClauseDecl& clause : clauses) names.push_back(clause.name);
  return names;
}

std::vector<std::string> keywordNames() {
  std::vector<std::string> names;
  for (const KeywordDecl& keyword : keywordTable()) names.push_back(keyword.name);
  return names;
}

}  // namespace cc::deck
