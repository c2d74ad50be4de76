// libFuzzer entry point for the deck parser (built with -DCOVCONTACT_FUZZ=ON and clang; see
// tests/fuzz/README.md for running it).
#include <cstddef>
#include <cstdint>

#include "deck_fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cc::fuzz::parseDeckBytes(data, size);  // accepted or rejected alike: only crashes count
  return 0;
}
