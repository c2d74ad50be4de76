// Tokenizer for deck text: comments, strings, punctuation, continuation lines, and locations.
#include "deck/deck_lexer.hpp"

#include <fmt/format.h>

#include <string_view>

#include "common/errors.hpp"

namespace cc::deck {

namespace {

constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";
constexpr std::string_view kWordDelimiters = "=\"(),#!";
constexpr char kDeleteCharacter = 0x7f;

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}
bool isControl(char c) {
  return (static_cast<unsigned char>(c) < 0x20 && !isBlank(c)) || c == kDeleteCharacter;
}
bool endsWord(char c) {
  return isBlank(c) || isControl(c) || kWordDelimiters.find(c) != std::string_view::npos;
}

Token::Kind punctuationKind(char c) {
  switch (c) {
    case '=':
      return Token::Kind::Equals;
    case '(':
      return Token::Kind::OpenParen;
    case ')':
      return Token::Kind::CloseParen;
    default:
      return Token::Kind::Comma;
  }
}

// Tokens of one physical line (comments removed).
std::vector<Token> tokenizePhysicalLine(std::string_view line, const std::string& file,
                                        int lineNumber) {
  std::vector<Token> tokens;
  std::size_t pos = 0;
  auto here = [&](std::size_t column) {
    return SourceLocation{file, lineNumber, static_cast<int>(column) + 1};
  };
  while (pos < line.size()) {
    const char c = line[pos];
    if (isBlank(c)) {
      ++pos;
    } else if (c == '#' || c == '!') {
      break;
    } else if (isControl(c)) {
      throw InputError(here(pos), fmt::format("unexpected control character (code {})",
                                              static_cast<int>(static_cast<unsigned char>(c))));
    } else if (c == '"') {
      const std::size_t close = line.find('"', pos + 1);
      if (close == std::string_view::npos) {
        throw InputError(here(pos), "unterminated string: missing closing '\"' on this line");
      }
      tokens.push_back(
          {Token::Kind::String, std::string(line.substr(pos + 1, close - pos - 1)), here(pos)});
      pos = close + 1;
    } else if (kWordDelimiters.find(c) != std::string_view::npos) {
      tokens.push_back({punctuationKind(c), std::string(1, c), here(pos)});
      ++pos;
    } else {
      const std::size_t start = pos;
      while (pos < line.size() && !endsWord(line[pos])) ++pos;
      tokens.push_back(
          {Token::Kind::Word, std::string(line.substr(start, pos - start)), here(start)});
    }
  }
  return tokens;
}

// Removes a trailing continuation mark ('\' or '&' ending the last word); true if there was one.
bool stripContinuation(std::vector<Token>& tokens, SourceLocation& markLocation) {
  if (tokens.empty() || !tokens.back().isWord()) return false;
  std::string& word = tokens.back().text;
  const char last = word.back();
  if (last != '\\' && last != '&') return false;
  markLocation = tokens.back().where;
  markLocation.column += static_cast<int>(word.size()) - 1;
  word.pop_back();
  if (word.empty()) tokens.pop_back();
  return true;
}

SourceLocation afterLastToken(const std::vector<Token>& tokens) {
  SourceLocation end = tokens.back().where;
  const Token& last = tokens.back();
  const std::size_t quotes = last.kind == Token::Kind::String ? 2 : 0;
  end.column += static_cast<int>(last.text.size() + quotes);
  return end;
}

}  // namespace

std::string describe(const Token& token) {
  switch (token.kind) {
    case Token::Kind::Word:
      return fmt::format("'{}'", token.text);
    case Token::Kind::String:
      return fmt::format("string \"{}\"", token.text);
    default:
      return fmt::format("'{}'", token.text);
  }
}

std::vector<LogicalLine> tokenize(const std::string& text, const std::string& file) {
  std::string_view rest(text);
  if (rest.starts_with(kUtf8ByteOrderMark)) rest.remove_prefix(kUtf8ByteOrderMark.size());
  std::vector<LogicalLine> lines;
  LogicalLine current;
  bool continuing = false;
  SourceLocation continuationMark;
  int lineNumber = 0;
  while (!rest.empty()) {
    ++lineNumber;
    const std::size_t newline = rest.find('\n');
    const std::string_view physical = rest.substr(0, newline);
    rest.remove_prefix(newline == std::string_view::npos ? rest.size() : newline + 1);
    std::vector<Token> tokens = tokenizePhysicalLine(physical, file, lineNumber);
    if (tokens.empty()) continue;  // blank or comment line (also inside a continued line)
    continuing = stripContinuation(tokens, continuationMark);
    current.tokens.insert(current.tokens.end(), tokens.begin(), tokens.end());
    if (!continuing && !current.tokens.empty()) {
      current.end = afterLastToken(current.tokens);
      lines.push_back(std::move(current));
      current = LogicalLine{};
    }
  }
  if (continuing) {
    throw InputError(continuationMark,
                     "line continuation at the end of the file: nothing follows it");
  }
  return lines;
}

}  // namespace cc::deck
