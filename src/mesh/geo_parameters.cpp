// A minimal scanner of the gmsh .geo language: just enough to list DefineConstant names and
// follow Include statements. It never evaluates anything; gmsh itself parses the file.
#include "mesh/geo_parameters.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace cc {
namespace {

// Guards against Include cycles and runaway recursion.
constexpr int kMaxIncludeDepth = 16;

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return {};
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool isIdentifierChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// The text with // and /* */ comments replaced by spaces (string literals kept intact).
std::string stripComments(const std::string& text) {
  std::string out = text;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i] == '"') {
      for (++i; i < out.size() && out[i] != '"'; ++i) {
        if (out[i] == '\\') ++i;
      }
    } else if (out.compare(i, 2, "//") == 0) {
      for (; i < out.size() && out[i] != '\n'; ++i) out[i] = ' ';
    } else if (out.compare(i, 2, "/*") == 0) {
      const std::size_t end = out.find("*/", i + 2);
      const std::size_t stop = end == std::string::npos ? out.size() : end + 2;
      for (; i < stop; ++i) out[i] = out[i] == '\n' ? '\n' : ' ';
      --i;
    }
  }
  return out;
}

// Positions just after each whole-word occurrence of `keyword` outside string literals.
std::vector<std::size_t> keywordEnds(const std::string& text, const std::string& keyword) {
  std::vector<std::size_t> ends;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '"') inString = !inString;
    if (inString || text.compare(i, keyword.size(), keyword) != 0) continue;
    const bool startsWord = i == 0 || !isIdentifierChar(text[i - 1]);
    const std::size_t end = i + keyword.size();
    const bool endsWord = end >= text.size() || !isIdentifierChar(text[end]);
    if (startsWord && endsWord) ends.push_back(end);
  }
  return ends;
}

std::size_t skipSpace(const std::string& text, std::size_t i) {
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  return i;
}

// Scans one DefineConstant[...] list starting at its '[': an entry is `name = value` or
// `name[] = value`; entries are separated by commas outside braces, brackets and parentheses.
void collectEntryNames(const std::string& text, std::size_t open, std::set<std::string>& names) {
  int depth = 0;
  bool expectName = true;
  for (std::size_t i = open; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') {
      i = text.find('"', i + 1);
      if (i == std::string::npos) return;
    } else if (c == '[' || c == '{' || c == '(') {
      ++depth;
    } else if (c == ']' || c == '}' || c == ')') {
      if (--depth == 0) return;
    } else if (c == ',' && depth == 1) {
      expectName = true;
    } else if (expectName && depth == 1 && isIdentifierChar(c)) {
      std::size_t end = i;
      while (end < text.size() && isIdentifierChar(text[end])) ++end;
      names.insert(text.substr(i, end - i));
      expectName = false;
      i = end - 1;
    }
  }
}

void scanFile(const std::filesystem::path& path, int depth, std::set<std::string>& names) {
  if (depth > kMaxIncludeDepth) return;
  const std::string text = stripComments(readFile(path));
  for (std::size_t end : keywordEnds(text, "DefineConstant")) {
    const std::size_t open = skipSpace(text, end);
    if (open < text.size() && text[open] == '[') collectEntryNames(text, open, names);
  }
  for (std::size_t end : keywordEnds(text, "Include")) {
    const std::size_t quote = skipSpace(text, end);
    if (quote >= text.size() || text[quote] != '"') continue;
    const std::size_t close = text.find('"', quote + 1);
    if (close == std::string::npos) continue;
    const std::filesystem::path included = text.substr(quote + 1, close - quote - 1);
    scanFile(included.is_absolute() ? included : path.parent_path() / included, depth + 1, names);
  }
}

}  // namespace

std::set<std::string> geoDefinedConstants(const std::string& geoPath) {
  std::set<std::string> names;
  scanFile(geoPath, 0, names);
  return names;
}

}  // namespace cc
