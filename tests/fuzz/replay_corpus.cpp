// Replays every file of the fuzz corpus (and any other files given) through the deck parser, as
// a regression test in every build: each must be accepted or rejected with an InputError.
// Usage: replay_deck_corpus DIRECTORY_OR_FILE...
#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

#include "deck_fuzz_input.hpp"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  std::vector<fs::path> inputs;
  for (int i = 1; i < argc; ++i) {
    if (fs::is_directory(argv[i])) {
      for (const auto& entry : fs::directory_iterator(argv[i])) {
        if (entry.is_regular_file()) inputs.push_back(entry.path());
      }
    } else {
      inputs.emplace_back(argv[i]);
    }
  }
  std::sort(inputs.begin(), inputs.end());
  if (inputs.empty()) {
    std::cerr << "replay_deck_corpus: no inputs\n";
    return 1;
  }
  int accepted = 0;
  for (const fs::path& input : inputs) {
    std::ifstream file(input, std::ios::binary);
    const std::vector<char> bytes{std::istreambuf_iterator<char>(file), {}};
    try {
      accepted += cc::fuzz::parseDeckBytes(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                           bytes.size());
    } catch (const std::exception& error) {
      std::cerr << input << ": the parser threw " << error.what() << "\n";
      return 1;
    }
  }
  std::cout << "replayed " << inputs.size() << " inputs: " << accepted << " parsed, "
            << inputs.size() - accepted << " rejected with an input error\n";
  return 0;
}
