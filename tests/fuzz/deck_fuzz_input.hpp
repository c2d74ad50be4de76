// One fuzz input for the deck parser: arbitrary bytes as the text of a deck. Shared by the
// libFuzzer target (fuzz_deck_parser) and the corpus replay that every build runs.
#pragma once

#include <cstddef>
#include <cstdint>

namespace cc::fuzz {

// Parses `data` as a deck: true when the parser accepts it, false when it rejects it with an
// InputError (the only way a deck may fail). Any other exception escapes, and a crash, hang or
// undefined behaviour shows under the fuzzer's sanitizers.
bool parseDeckBytes(const std::uint8_t* data, std::size_t size);

}  // namespace cc::fuzz
