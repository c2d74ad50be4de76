// Verification deck paths, text and single-line variants for the issue-2 tests.
#include "core_decks.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cc::test {

std::string coreDeckPath(const std::string& name) {
  return std::string(COVCONTACT_SOURCE_DIR) + "/input/verification/core/" + name;
}

std::string readText(const std::string& path) {
  std::ifstream stream(path);
  if (!stream) throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

std::string replaceLine(const std::string& text, const std::string& keyword,
                        const std::string& line) {
  std::istringstream input(text);
  std::string result, current;
  int matches = 0;
  while (std::getline(input, current)) {
    if (current.rfind(keyword + " ", 0) == 0) {
      current = line;
      ++matches;
    }
    result += current + "\n";
  }
  if (matches != 1) {
    throw std::invalid_argument("expected one line starting with '" + keyword + "', found " +
                                std::to_string(matches));
  }
  return result;
}

}  // namespace cc::test
