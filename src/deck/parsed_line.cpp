// Interprets one logical deck line against its keyword declaration (types, ranges, defaults,
// required parameters, clauses) and reports the first problem with its exact location.
#include "deck/parsed_line.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "common/errors.hpp"
#include "common/name_matching.hpp"

namespace cc::deck {

namespace {

const std::vector<std::string> kBoolTrue = {"yes", "true"};
const std::vector<std::string> kBoolFalse = {"no", "false"};
constexpr const char* kTableWord = "table";

// "a number > 0", "one of svk, neohooke", ...: what a value must look like.
std::string expectation(const ValueDecl& decl) {
  const std::string range = decl.range.describe();
  const std::string restriction = range.empty() ? "" : " " + range;
  switch (decl.type) {
    case ValueType::Number:
      return "a number" + restriction;
    case ValueType::Integer:
      return "an integer" + restriction;
    case ValueType::String:
      return "a quoted string";
    case ValueType::Identifier:
      return "a name";
    case ValueType::Enum:
      return "one of " + joinAlternatives(decl.choices);
    case ValueType::EnumList:
      return "a comma-separated list of " + joinAlternatives(decl.choices);
    case ValueType::Vector:
      return "a vector (x,y,z)";
    case ValueType::Bool:
      return "yes or no";
  }
  return "a value";
}

}  // namespace

std::string parseNumberText(const std::string& text, double& number) {
  if (text.empty()) return "empty number";
  errno = 0;
  char* end = nullptr;
  number = std::strtod(text.c_str(), &end);
  if (end == text.c_str()) return fmt::format("'{}' is not a number", text);
  if (*end != '\0') {
    const std::string valid = text.substr(0, static_cast<std::size_t>(end - text.c_str()));
    return fmt::format("'{}' is not a valid number (unexpected '{}' after '{}')", text, end, valid);
  }
  if (!std::isfinite(number)) {
    return fmt::format("'{}' is not a finite number", text);
  }
  return "";
}

std::string parseIntegerText(const std::string& text, long long& integer) {
  const char* begin = text.c_str();
  const char* end = begin + text.size();
  if (begin != end && *begin == '+') ++begin;
  const auto [stop, error] = std::from_chars(begin, end, integer);
  if (error == std::errc::result_out_of_range ||
      (error == std::errc() && stop == end && (integer > INT_MAX || integer < INT_MIN))) {
    return fmt::format("'{}' is too large for an integer", text);
  }
  if (error != std::errc() || stop != end || begin == end) {
    return fmt::format("'{}' is not an integer", text);
  }
  return "";
}

// Reads tokens [pos, end) of a line into a ParsedLine.
class LineReader {
 public:
  LineReader(const std::vector<Token>& tokens, std::size_t start, const SourceLocation& lineEnd,
             ParsedLine& out)
      : tokens_(tokens), pos_(start), lineEnd_(lineEnd), out_(out) {}

  void readLine();
  Value readValue(const ValueDecl& decl, bool positional);

 private:
  bool atEnd() const { return pos_ >= tokens_.size(); }
  const Token& peek() const { return tokens_[pos_]; }
  bool startsParameter() const {
    return !atEnd() && peek().isWord() && pos_ + 1 < tokens_.size() &&
           tokens_[pos_ + 1].kind == Token::Kind::Equals;
  }
  const SourceLocation& nextLocation() const { return atEnd() ? lineEnd_ : peek().where; }
  [[noreturn]] void fail(const SourceLocation& where, const std::string& message) const {
    out_.fail(where, message);
  }

  void readParameter();
  void readPositional();
  void readClause();
  void readClauseArgument(Clause& clause);
  void applyDefaults();
  void takeContextFromParameter();
  const Token& takeValueToken(const ValueDecl& decl, bool positional);
  double readNumber(const std::string& label, const std::string& what);
  std::vector<std::pair<double, double>> readPoints(const std::string& label);
  void expectPunctuation(Token::Kind kind, const std::string& label, const std::string& what);
  std::string resolveChoice(const Token& token, const ValueDecl& decl);
  void readVector(const ValueDecl& decl, Value& value);
  void readChoiceList(const Token& first, const ValueDecl& decl, Value& value);
  void checkRange(const Token& token, const ValueDecl& decl, double number) const;
  double checkedNumber(const Token& token, const ValueDecl& decl) const;
  long long checkedInteger(const Token& token, const ValueDecl& decl) const;
  bool checkedBool(const Token& token, const ValueDecl& decl) const;

  const std::vector<Token>& tokens_;
  std::size_t pos_;
  SourceLocation lineEnd_;
  ParsedLine& out_;
};

void LineReader::readLine() {
  takeContextFromParameter();
  const KeywordDecl& keyword = out_.keyword();
  while (!atEnd()) {
    if (startsParameter()) {
      readParameter();
    } else if (peek().kind == Token::Kind::Equals) {
      fail(peek().where, "'=' must follow a parameter name (write NAME=VALUE)");
    } else if (out_.positionals_.size() < keyword.positionals.size()) {
      readPositional();
    } else {
      readClause();
    }
  }
  if (out_.positionals_.size() < keyword.positionals.size()) {
    const ValueDecl& missing = keyword.positionals[out_.positionals_.size()];
    fail(lineEnd_, fmt::format("missing {} ({}: {})", missing.name, expectation(missing),
                               missing.description));
  }
  applyDefaults();
}

void LineReader::takeContextFromParameter() {
  const KeywordDecl& keyword = out_.keyword();
  if (keyword.findParameter(keyword.itemName) == nullptr) return;
  for (std::size_t i = pos_; i + 2 < tokens_.size(); ++i) {
    if (tokens_[i].isWord() && equalsIgnoreCase(tokens_[i].text, keyword.itemName) &&
        tokens_[i + 1].kind == Token::Kind::Equals && tokens_[i + 2].isText()) {
      out_.context_ = fmt::format("{} '{}'", keyword.name, tokens_[i + 2].text);
    }
  }
}

void LineReader::readParameter() {
  const KeywordDecl& keyword = out_.keyword();
  const Token& nameToken = tokens_[pos_];
  pos_ += 2;  // name and '='
  const std::vector<std::string> names = keyword.parameterNames();
  const NameMatch match = matchName(nameToken.text, names);
  if (!match.ambiguousWith.empty()) {
    std::vector<std::string> candidates;
    for (int index : match.ambiguousWith) candidates.push_back(names[index]);
    fail(nameToken.where, fmt::format("ambiguous parameter '{}': could be {}", nameToken.text,
                                      joinAlternatives(candidates)));
  }
  if (!match.found()) {
    if (!keyword.extraNumbers.empty()) {
      for (const ExtraNumber& extra : out_.extraNumbers_) {
        if (extra.name == nameToken.text) {
          fail(nameToken.where, fmt::format("parameter '{}' given twice (first at {})", extra.name,
                                            extra.where.str()));
        }
      }
      const double number = readNumber(nameToken.text, "a number");
      out_.extraNumbers_.push_back({nameToken.text, number, nameToken.where});
      return;
    }
    if (names.empty()) {
      fail(nameToken.where, fmt::format("unknown parameter '{}': '{}' takes no NAME=VALUE "
                                        "parameters",
                                        nameToken.text, keyword.name));
    }
    const std::string hint = didYouMean(nameToken.text, names);
    fail(nameToken.where,
         fmt::format("unknown parameter '{}'{}", nameToken.text,
                     hint.empty() ? "; expected one of " + joinAlternatives(names) : hint));
  }
  const ValueDecl& decl = keyword.parameters[match.index];
  const auto previous = out_.parameters_.find(decl.name);
  if (previous != out_.parameters_.end()) {
    fail(nameToken.where, fmt::format("parameter '{}' given twice (first at {})", decl.name,
                                      previous->second.where.str()));
  }
  out_.parameters_[decl.name] = readValue(decl, false);
}

void LineReader::readPositional() {
  const KeywordDecl& keyword = out_.keyword();
  const ValueDecl& decl = keyword.positionals[out_.positionals_.size()];
  // A clause word where the positional should be means the positional was left out
  // (`fix uz`), except the built-in node set `all`, which is also fix's component word: the
  // first word is the SET (`fix all uz`), and `fix all` alone is left to the handler to explain.
  const bool builtInSet = decl.nodeSet && peek().isWord() && peek().text == kAllNodesSet;
  if (peek().isWord() && decl.type == ValueType::Identifier && !builtInSet) {
    const NameMatch clause = matchName(peek().text, keyword.clauseNames());
    if (clause.found() && equalsIgnoreCase(peek().text, keyword.clauses[clause.index].name)) {
      fail(peek().where,
           fmt::format("missing {} before '{}' ({})", decl.name, peek().text, decl.description));
    }
  }
  Value value = readValue(decl, true);
  if (keyword.itemName == decl.name) {
    out_.context_ = fmt::format("{} '{}'", keyword.name, value.text);
  }
  out_.positionals_.push_back(std::move(value));
}

void LineReader::readClause() {
  const KeywordDecl& keyword = out_.keyword();
  const Token& word = peek();
  const std::vector<std::string> clauseNames = keyword.clauseNames();
  std::string expected = clauseNames.empty() ? "" : joinAlternatives(clauseNames);
  if (!keyword.parameters.empty() || !keyword.extraNumbers.empty()) {
    expected += expected.empty() ? "NAME=VALUE parameters" : " or NAME=VALUE parameters";
  }
  if (expected.empty()) expected = "nothing more on this line";
  if (!word.isWord())
    fail(word.where, fmt::format("unexpected {}; expected {}", describe(word), expected));
  const NameMatch match = matchName(word.text, clauseNames);
  if (!match.found()) {
    const NameMatch parameter = matchName(word.text, keyword.parameterNames());
    if (parameter.found()) {
      const std::string& name = keyword.parameters[parameter.index].name;
      fail(word.where, fmt::format("parameter '{}' needs a value: write {}=VALUE", name, name));
    }
    std::vector<std::string> candidates = clauseNames;
    for (const std::string& name : keyword.parameterNames()) candidates.push_back(name);
    fail(word.where, fmt::format("unexpected word '{}'{}; expected {}", word.text,
                                 didYouMean(word.text, candidates), expected));
  }
  Clause clause;
  clause.decl = &keyword.clauses[match.index];
  clause.where = word.where;
  if (const Clause* previous = out_.findClause(clause.decl->name)) {
    fail(word.where,
         fmt::format("'{}' given twice (first at {})", clause.decl->name, previous->where.str()));
  }
  ++pos_;
  readClauseArgument(clause);
  out_.clauses_.push_back(std::move(clause));
}

void LineReader::readClauseArgument(Clause& clause) {
  const std::string& label = clause.decl->name;
  switch (clause.decl->argument) {
    case ClauseDecl::Argument::None:
      return;
    case ClauseDecl::Argument::Points:
      clause.points = readPoints(label);
      return;
    case ClauseDecl::Argument::Identifier: {
      if (atEnd() || !peek().isText() || startsParameter()) {
        fail(nextLocation(), fmt::format("'{}' must be followed by a name", label));
      }
      clause.identifier = peek().text;
      clause.identifierWhere = peek().where;
      ++pos_;
      return;
    }
    case ClauseDecl::Argument::Function:
      break;
  }
  const std::string expected =
      "a quoted expression such as \"0.1*t\", a number or 'table (t,v) (t,v) ...'";
  if (atEnd()) fail(lineEnd_, fmt::format("'{}' must be followed by {}", label, expected));
  const Token& token = peek();
  FunctionSpec function;
  function.where = token.where;
  double constant = 0;
  if (token.kind == Token::Kind::String) {
    if (token.text.find_first_not_of(" \t") == std::string::npos) {
      fail(token.where, fmt::format("{}: empty expression", label));
    }
    function.expression = token.text;
    ++pos_;
  } else if (token.isWord() && equalsIgnoreCase(token.text, kTableWord)) {
    ++pos_;
    function.kind = FunctionSpec::Kind::Table;
    function.table = readPoints(label + " table");
  } else if (token.isWord() && parseNumberText(token.text, constant).empty()) {
    function.expression = token.text;
    ++pos_;
  } else {
    fail(token.where, fmt::format("{}: expected {}, got {}", label, expected, describe(token)));
  }
  clause.function = std::move(function);
}

const Token& LineReader::takeValueToken(const ValueDecl& decl, bool positional) {
  if (atEnd() || startsParameter()) {
    if (positional) {
      fail(nextLocation(),
           fmt::format("missing {} ({}: {})", decl.name, expectation(decl), decl.description));
    }
    fail(nextLocation(),
         fmt::format("{}= has no value; expected {}", decl.name, expectation(decl)));
  }
  const Token& token = tokens_[pos_++];
  const bool textAllowed = decl.type == ValueType::String || decl.type == ValueType::Identifier;
  if (!(token.isWord() || (textAllowed && token.kind == Token::Kind::String))) {
    fail(token.where,
         fmt::format("{}: expected {}, got {}", decl.name, expectation(decl), describe(token)));
  }
  return token;
}

Value LineReader::readValue(const ValueDecl& decl, bool positional) {
  Value value;
  value.decl = &decl;
  value.given = true;
  value.where = nextLocation();
  if (decl.type == ValueType::Vector) {
    readVector(decl, value);
    return value;
  }
  const Token& token = takeValueToken(decl, positional);
  value.raw = token.text;
  value.text = token.text;
  switch (decl.type) {
    case ValueType::Number:
      value.number = checkedNumber(token, decl);
      break;
    case ValueType::Integer:
      value.integer = checkedInteger(token, decl);
      break;
    case ValueType::String:
    case ValueType::Identifier:
      if (token.text.empty()) {
        fail(token.where, fmt::format("{}: empty {}", decl.name,
                                      decl.type == ValueType::String ? "string" : "name"));
      }
      break;
    case ValueType::Enum:
      value.text = resolveChoice(token, decl);
      break;
    case ValueType::EnumList:
      readChoiceList(token, decl, value);
      break;
    case ValueType::Bool:
      value.flag = checkedBool(token, decl);
      break;
    case ValueType::Vector:
      break;
  }
  return value;
}

void LineReader::readVector(const ValueDecl& decl, Value& value) {
  const std::size_t first = pos_;
  expectPunctuation(Token::Kind::OpenParen, decl.name, expectation(decl));
  for (std::size_t i = 0; i < 3; ++i) {
    value.vector[i] = readNumber(decl.name, expectation(decl));
    expectPunctuation(i < 2 ? Token::Kind::Comma : Token::Kind::CloseParen, decl.name,
                      expectation(decl));
  }
  for (std::size_t i = first; i < pos_; ++i) value.raw += tokens_[i].text;
}

void LineReader::checkRange(const Token& token, const ValueDecl& decl, double number) const {
  if (!decl.range.contains(number)) {
    fail(token.where,
         fmt::format("{} must be {}, got {}", decl.name, decl.range.describe(), token.text));
  }
}

double LineReader::checkedNumber(const Token& token, const ValueDecl& decl) const {
  double number = 0;
  const std::string error = parseNumberText(token.text, number);
  if (!error.empty()) fail(token.where, fmt::format("{}: {}", decl.name, error));
  checkRange(token, decl, number);
  return number;
}

long long LineReader::checkedInteger(const Token& token, const ValueDecl& decl) const {
  long long integer = 0;
  const std::string error = parseIntegerText(token.text, integer);
  if (!error.empty()) fail(token.where, fmt::format("{}: {}", decl.name, error));
  checkRange(token, decl, static_cast<double>(integer));
  return integer;
}

bool LineReader::checkedBool(const Token& token, const ValueDecl& decl) const {
  const std::string lower = toLower(token.text);
  const bool isTrue = lower == kBoolTrue[0] || lower == kBoolTrue[1];
  const bool isFalse = lower == kBoolFalse[0] || lower == kBoolFalse[1];
  if (!isTrue && !isFalse) {
    fail(token.where, fmt::format("{} must be yes or no, got '{}'", decl.name, token.text));
  }
  return isTrue;
}

void LineReader::readChoiceList(const Token& first, const ValueDecl& decl, Value& value) {
  value.list.push_back(resolveChoice(first, decl));
  while (!atEnd() && peek().kind == Token::Kind::Comma) {
    ++pos_;
    const Token& item = takeValueToken(decl, false);
    const std::string choice = resolveChoice(item, decl);
    for (const std::string& earlier : value.list) {
      if (earlier == choice) {
        fail(item.where, fmt::format("{}: '{}' listed twice", decl.name, choice));
      }
    }
    value.list.push_back(choice);
    value.raw += "," + item.text;
  }
}

std::string LineReader::resolveChoice(const Token& token, const ValueDecl& decl) {
  const NameMatch match = matchName(token.text, decl.choices);
  if (match.found()) return decl.choices[match.index];
  fail(token.where,
       fmt::format("{} must be one of {}, got '{}'{}", decl.name, joinAlternatives(decl.choices),
                   token.text, didYouMean(token.text, decl.choices)));
}

double LineReader::readNumber(const std::string& label, const std::string& what) {
  if (atEnd() || startsParameter()) {
    fail(nextLocation(), fmt::format("{}: missing value; expected {}", label, what));
  }
  const Token& token = tokens_[pos_++];
  if (!token.isWord()) {
    fail(token.where, fmt::format("{}: expected {}, got {}", label, what, describe(token)));
  }
  double number = 0;
  const std::string error = parseNumberText(token.text, number);
  if (!error.empty()) fail(token.where, fmt::format("{}: {}", label, error));
  return number;
}

void LineReader::expectPunctuation(Token::Kind kind, const std::string& label,
                                   const std::string& what) {
  if (atEnd() || peek().kind != kind) {
    const std::string got = atEnd() ? "the end of the line" : describe(peek());
    fail(nextLocation(), fmt::format("{}: expected {}, got {}", label, what, got));
  }
  ++pos_;
}

std::vector<std::pair<double, double>> LineReader::readPoints(const std::string& label) {
  const std::string what = "a point (t,v)";
  std::vector<std::pair<double, double>> points;
  do {
    const SourceLocation pointWhere = nextLocation();
    expectPunctuation(Token::Kind::OpenParen, label, what);
    const double time = readNumber(label, what);
    expectPunctuation(Token::Kind::Comma, label, what);
    const double value = readNumber(label, what);
    expectPunctuation(Token::Kind::CloseParen, label, what);
    if (!points.empty() && time <= points.back().first) {
      fail(pointWhere, fmt::format("{}: t must increase strictly from point to point, but "
                                   "t={} follows t={}",
                                   label, time, points.back().first));
    }
    points.emplace_back(time, value);
  } while (!atEnd() && peek().kind == Token::Kind::OpenParen);
  return points;
}

void LineReader::applyDefaults() {
  for (const ValueDecl& decl : out_.keyword().parameters) {
    if (out_.parameters_.count(decl.name) != 0) continue;
    if (decl.required) {
      fail(out_.where(), fmt::format("missing required parameter {}= ({}, {})", decl.name,
                                     decl.description, expectation(decl)));
    }
    if (decl.defaultText.empty()) continue;
    const std::vector<LogicalLine> defaultLine = tokenize(decl.defaultText, "<default>");
    LineReader reader(defaultLine.front().tokens, 0, defaultLine.front().end, out_);
    Value value = reader.readValue(decl, false);
    value.given = false;
    value.where = out_.where();
    out_.parameters_[decl.name] = std::move(value);
  }
}

ParsedLine::ParsedLine(const LogicalLine& line, const KeywordDecl& keyword)
    : keyword_(&keyword),
      where_(line.tokens.front().where),
      end_(line.end),
      context_(keyword.name) {
  LineReader reader(line.tokens, 1, line.end, *this);
  reader.readLine();
}

bool ParsedLine::given(const std::string& parameter) const {
  const auto found = parameters_.find(parameter);
  return found != parameters_.end() && found->second.given;
}

const Value& ParsedLine::value(const std::string& parameter) const {
  const auto found = parameters_.find(parameter);
  if (found == parameters_.end()) {
    throw std::logic_error(
        fmt::format("deck: '{}' has no value and no default for {}", parameter, keyword_->name));
  }
  return found->second;
}

int ParsedLine::integer(const std::string& parameter) const {
  return static_cast<int>(value(parameter).integer);
}

const Clause* ParsedLine::findClause(const std::string& name) const {
  for (const Clause& clause : clauses_) {
    if (clause.decl->name == name) return &clause;
  }
  return nullptr;
}

void ParsedLine::fail(const SourceLocation& where, const std::string& message) const {
  throw InputError(where, context_ + ": " + message);
}

}  // namespace cc::deck
