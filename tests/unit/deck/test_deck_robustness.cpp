// Robustness: thousands of randomly damaged decks (deterministic seed) must each either parse or
// throw InputError; never crash, hang, or throw anything else.
#include <gtest/gtest.h>

#include <random>

#include "deck_test_utils.hpp"

namespace cc::test {
namespace {

const std::string kSeedDeck = R"deck(title "robustness seed"
mesh "meshes/two_blocks.geo" n=2
material soft svk E=2.1e4 nu=0.3
elements block solid_shell8 material=soft thickness=z eas=1
elements base hex8 material=soft
fix base_bottom all
prescribe block_top uz "-0.1*t" ux table (0,0) (1,0.5)
load block_top fy 2.5 total
rigid ball sphere origin=(0.5,0.5,1.5) radius=0.25 uz "-0.2*t"
contact sts master=block_bottom slave=base_top eps_n=2.1e6 eps_t=1e5 mu=0.3 \
   tangent=no_curvature name=interface
contact stas master=block_top slave=ball eps_n=1e5 parts=normal_main,stick_main
output file="run.h5" fields=displacement,stress csv=no
reference reaction:block_top:z table (0,0) (1,-3)
solve
  newton maxit=12 converge=both
  steps 2 dt=0.5 cutback_max=2
end
)deck";

// Characters that matter to the lexer and the grammar, plus ordinary ones.
const std::string kInterestingCharacters = "=(),\"#!\\&-+.eE0123456789 \n\tx_:";

std::string mutate(std::string text, std::mt19937& random) {
  std::uniform_int_distribution<std::size_t> position(0, text.size() - 1);
  std::uniform_int_distribution<std::size_t> character(0, kInterestingCharacters.size() - 1);
  std::uniform_int_distribution<int> operation(0, 3);
  const std::size_t at = position(random);
  switch (operation(random)) {
    case 0:
      text.erase(at, 1);
      break;
    case 1:
      text.insert(at, 1, kInterestingCharacters[character(random)]);
      break;
    case 2:
      text[at] = kInterestingCharacters[character(random)];
      break;
    default: {
      const std::size_t length = std::min<std::size_t>(12, text.size() - at);
      text.insert(position(random), text.substr(at, length));
    }
  }
  return text;
}

TEST(DeckRobustness, DamagedDecksFailOnlyWithInputErrors) {
  constexpr int kDecks = 3000;
  constexpr int kMaxMutationsPerDeck = 4;
  std::mt19937 random(20260611);
  std::uniform_int_distribution<int> mutations(1, kMaxMutationsPerDeck);
  int rejected = 0;
  ASSERT_NO_THROW(parseDeckText(kSeedDeck, virtualDeckPath()));
  for (int i = 0; i < kDecks; ++i) {
    std::string deck = kSeedDeck;
    for (int m = mutations(random); m > 0; --m) deck = mutate(deck, random);
    try {
      parseDeckText(deck, virtualDeckPath());
    } catch (const InputError& error) {
      ++rejected;
      EXPECT_TRUE(error.where().known()) << error.what();
    } catch (const std::exception& other) {
      ADD_FAILURE() << "non-input exception " << other.what() << " for deck:\n" << deck;
    }
  }
  // Most single-character damage is detected (a few mutations only touch comments or strings).
  EXPECT_GT(rejected, kDecks / 2);
}

}  // namespace
}  // namespace cc::test
