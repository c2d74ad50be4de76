// Helpers of the robustness tests (see stress_support.hpp).
#include "stress_support.hpp"

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace cc::test {

namespace fs = std::filesystem;

std::string stressDeck(const std::string& name) {
  return std::string(COVCONTACT_SOURCE_DIR) + "/input/stress/" + name + ".deck";
}

std::string readText(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

std::string replaceOnce(const std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos || text.find(from, at + 1) != std::string::npos) {
    throw std::invalid_argument("'" + from + "' does not occur exactly once");
  }
  return text.substr(0, at) + to + text.substr(at + from.size());
}

DeckRun runStressDeck(const std::string& name) {
  return runDeckFile(stressDeck(name));
}

DeckRun runStressText(const std::string& text, const std::string& name) {
  return runDeckText(text, stressDeck(name));
}

ContactSums contactSums(const ContactPairRecord& pair, double friction) {
  ContactSums sums;
  for (Eigen::Index i = 0; i < pair.state.size(); ++i) {
    const auto state = static_cast<ContactState>(pair.state[i]);
    if (state == ContactState::Open) {
      ++sums.open;
      continue;
    }
    const double normal = std::abs(pair.normalTraction[i]);
    const double tangential = pair.tangentialTraction.col(i).norm();
    sums.normal += normal * pair.weight[i];
    sums.tangential += tangential * pair.weight[i];
    if (state == ContactState::Stick) {
      ++sums.stick;
    } else {
      ++sums.slip;
      sums.worstConeError = std::max(
          sums.worstConeError, std::abs(tangential - friction * normal) / (friction * normal));
    }
  }
  return sums;
}

StackSolution compressedStack(double youngsModulus, double height, double area, double penalty,
                              double shortening) {
  // Unknown: the gap g <= 0. Stretch lambda = 1 - (shortening + g) / height; equilibrium
  // -eps_N g = lambda E (lambda^2 - 1) / 2 * (-1). Bisection on [-shortening, 0].
  auto residual = [&](double gap) {
    const double stretch = 1 - (shortening + gap) / height;
    return -penalty * gap + stretch * youngsModulus * (stretch * stretch - 1) / 2;
  };
  double low = -shortening, high = 0;
  for (int i = 0; i < 200 && high - low > 1e-300; ++i) {
    const double middle = 0.5 * (low + high);
    (residual(middle) > 0 ? low : high) = middle;
  }
  const double gap = 0.5 * (low + high);
  return {-penalty * gap * area, gap};
}

std::string scratchDirectory(const std::string& name) {
  const fs::path directory = fs::path(STRESS_SCRATCH_DIR) / name;
  fs::remove_all(directory);
  fs::create_directories(directory);
  return directory.string();
}

CommandResult runCovcontact(const std::string& arguments, const std::string& directory) {
  fs::create_directories(directory);
  // The captured streams sit beside the directory, so that a test can assert what the command
  // itself created in it.
  const std::string out = directory + ".stdout.txt", err = directory + ".stderr.txt";
  const std::string command = "cd '" + directory + "' && '" + COVCONTACT_EXECUTABLE + "' " +
                              arguments + " > '" + out + "' 2> '" + err + "'";
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.output = readText(out);
  result.error = readText(err);
  return result;
}

}  // namespace cc::test
