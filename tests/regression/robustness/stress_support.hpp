// Shared helpers of the robustness tests: the decks of input/stress and variants of them, the
// contact quantities the tests assert (Coulomb ratio, states), the closed-form compression of a
// nu = 0 stack, and running the real `covcontact` command.
#pragma once

#include <string>
#include <vector>

#include "deck_runner.hpp"

namespace cc::test {

// Absolute path of input/stress/<name>.deck.
std::string stressDeck(const std::string& name);
std::string readText(const std::string& path);
// `text` with its only occurrence of `from` replaced; throws std::invalid_argument unless
// `from` occurs exactly once, so a variant can never silently run the unmodified deck.
std::string replaceOnce(const std::string& text, const std::string& from, const std::string& to);

DeckRun runStressDeck(const std::string& name);
// Runs `text` as if it were input/stress/<name>.deck (relative paths resolve there).
DeckRun runStressText(const std::string& text, const std::string& name);

// Sums over the points of one pair in one step.
struct ContactSums {
  int open = 0, stick = 0, slip = 0;
  double normal = 0;      // sum |N| w
  double tangential = 0;  // sum |T| w
  // Largest | |T| - mu |N| | / (mu |N|) over slipping points: how exactly they sit on the cone.
  double worstConeError = 0;
  int active() const { return stick + slip; }
};
ContactSums contactSums(const ContactPairRecord& pair, double friction);

// Total force on a stack of nu = 0 St. Venant-Kirchhoff layers of total height `height`, one
// material (E), reference area `area`, shortened by `shortening` in all, with a penalty contact
// eps_N in series between two of them (homogeneous uniaxial compression: lambda E (lambda^2 - 1)
// / 2 per reference area, N = eps_N g per (unchanged, nu = 0) area). Also returns the gap g.
struct StackSolution {
  double force = 0;
  double gap = 0;
};
StackSolution compressedStack(double youngsModulus, double height, double area, double penalty,
                              double shortening);

// `covcontact ARGS` run through the shell in `directory` (created), stdout and stderr captured.
struct CommandResult {
  int exitCode = -1;
  std::string output;
  std::string error;
};
CommandResult runCovcontact(const std::string& arguments, const std::string& directory);
// An empty scratch directory for one test under the build tree.
std::string scratchDirectory(const std::string& name);

}  // namespace cc::test
