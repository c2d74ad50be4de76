// Tokenizer for deck text: splits a file into logical lines (joining continuation lines) of
// words, quoted strings and punctuation, each token carrying its file:line:column.
#pragma once

#include <string>
#include <vector>

#include "common/source_location.hpp"

namespace cc::deck {

struct Token {
  enum class Kind { Word, String, Equals, OpenParen, CloseParen, Comma };
  Kind kind = Kind::Word;
  std::string text;  // a word as written, a string without its quotes, or the punctuation
  SourceLocation where;

  bool isWord() const { return kind == Kind::Word; }
  bool isText() const { return kind == Kind::Word || kind == Kind::String; }
};

// "'word'", "string \"text\"" or "'('" for messages.
std::string describe(const Token& token);

struct LogicalLine {
  std::vector<Token> tokens;  // never empty
  SourceLocation end;         // just after the last token: where a missing item would go
};

// Lexical rules (documented in input/README.md): '#' and '!' start a comment outside strings;
// strings are "..." on one line without escapes; '=', '(', ')' and ',' are single tokens; a
// line whose last token ends in '\' or '&' continues on the next line that is not blank or a
// comment. Throws InputError on an unterminated string, a control character or a dangling
// continuation at the end of the file.
std::vector<LogicalLine> tokenize(const std::string& text, const std::string& file);

}  // namespace cc::deck
