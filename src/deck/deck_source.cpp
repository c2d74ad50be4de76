// Include resolution: nested includes relative to the including file, cycle detection by
// canonical path, and the combined deck text.
#include "deck/deck_source.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "common/errors.hpp"
#include "common/name_matching.hpp"
#include "common/utf8.hpp"
#include "deck/keyword_decl.hpp"
#include "deck/parsed_line.hpp"

namespace cc::deck {

namespace fs = std::filesystem;

namespace {

constexpr const char* kIncludeKeyword = "include";

struct OpenFile {
  std::string displayPath;  // as shown in messages
  fs::path identity;        // canonical, for cycle detection
};

class IncludeExpander {
 public:
  explicit IncludeExpander(DeckSource& out) : out_(out) {}
  void expand(const std::string& text, const OpenFile& file);

 private:
  const KeywordDecl& includeDecl() const;
  bool isInclude(const LogicalLine& line) const;
  void include(const LogicalLine& line, const OpenFile& from);

  DeckSource& out_;
  std::vector<OpenFile> stack_;
  std::set<fs::path> appended_;
};

fs::path identityOf(const std::string& path) {
  std::error_code error;
  const fs::path canonical = fs::weakly_canonical(fs::absolute(path), error);
  return error ? fs::absolute(path).lexically_normal() : canonical;
}

const KeywordDecl& IncludeExpander::includeDecl() const {
  for (const KeywordDecl& keyword : keywordTable()) {
    if (keyword.name == kIncludeKeyword) return keyword;
  }
  throw std::logic_error("deck: include is not declared");
}

bool IncludeExpander::isInclude(const LogicalLine& line) const {
  const Token& first = line.tokens.front();
  if (!first.isWord()) return false;
  const std::vector<std::string> names = keywordNames();
  const NameMatch match = matchName(first.text, names);
  return match.found() && names[match.index] == kIncludeKeyword;
}

void IncludeExpander::expand(const std::string& text, const OpenFile& file) {
  stack_.push_back(file);
  for (LogicalLine& line : tokenize(text, file.displayPath)) {
    if (isInclude(line)) {
      include(line, file);
    } else {
      out_.lines.push_back(std::move(line));
    }
  }
  stack_.pop_back();
}

void IncludeExpander::include(const LogicalLine& line, const OpenFile& from) {
  const ParsedLine parsed(line, includeDecl());
  const Value& path = parsed.positional(0);
  const fs::path given(path.text);
  const fs::path joined =
      given.is_absolute() ? given : fs::path(from.displayPath).parent_path() / given;
  const OpenFile target{joined.lexically_normal().string(), identityOf(joined.string())};
  for (std::size_t i = 0; i < stack_.size(); ++i) {
    if (stack_[i].identity != target.identity) continue;
    std::string cycle;
    for (std::size_t j = i; j < stack_.size(); ++j) cycle += stack_[j].displayPath + " -> ";
    throw InputError(path.where, fmt::format("include cycle: {}{}", cycle, target.displayPath));
  }
  if (stack_.size() >= kMaxIncludeDepth) {
    throw InputError(path.where,
                     fmt::format("includes nested more than {} deep (from {}): flatten the chain",
                                 kMaxIncludeDepth, stack_.front().displayPath));
  }
  const std::string text = readDeckFile(
      target.displayPath, path.where,
      fmt::format("include file '{}' (looked for '{}')", path.text, target.identity.string()));
  if (appended_.insert(target.identity).second) {
    out_.files.push_back(target.identity.string());
    out_.text += fmt::format("\n# ---- included file: {} ----\n", target.displayPath);
    out_.text += text;
  }
  expand(text, target);
}

}  // namespace

std::string readDeckFile(const std::string& path, const SourceLocation& requestedAt,
                         const std::string& what) {
  std::error_code error;
  if (fs::is_directory(path, error)) {
    throw InputError(requestedAt, fmt::format("cannot read {}: it is a directory", what));
  }
  // A device or pipe (include "/dev/zero", "/dev/stdin") would be read forever or block.
  if (fs::exists(path, error) && !fs::is_regular_file(path, error)) {
    throw InputError(requestedAt, fmt::format("cannot read {}: it is not a regular file", what));
  }
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw InputError(requestedAt, fmt::format("cannot open {}", what));
  std::ostringstream contents;
  contents << stream.rdbuf();
  if (stream.bad()) throw InputError(requestedAt, fmt::format("cannot read {}", what));
  std::string text = contents.str();
  if (text.find('\0') != std::string::npos) {
    throw InputError(requestedAt, fmt::format("{} is not a text file", what));
  }
  // Names from the deck end up in the XDMF file (XML) and the deck text in a UTF-8 attribute: a
  // Latin-1 byte there makes them invalid, so it is refused where it stands.
  if (const auto bad = firstInvalidUtf8(text)) {
    const std::size_t lineStart =
        text.rfind('\n', *bad) == std::string::npos ? 0 : text.rfind('\n', *bad) + 1;
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + *bad, '\n'));
    const int column = 1 + static_cast<int>(*bad - lineStart);
    throw InputError(SourceLocation{path, line, column},
                     fmt::format("byte 0x{:02x} is not UTF-8 text (or is a control character); "
                                 "save the file as UTF-8",
                                 static_cast<unsigned char>(text[*bad])));
  }
  return text;
}

DeckSource loadDeckSource(const std::string& text, const std::string& path) {
  DeckSource source;
  source.text = text;
  source.files.push_back(identityOf(path).string());
  IncludeExpander expander(source);
  expander.expand(text, OpenFile{path, identityOf(path)});
  return source;
}

}  // namespace cc::deck
