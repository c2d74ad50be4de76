// Reaction/contact-force CSV writer (RFC 4180 quoting for names containing commas or quotes).
#include "output/reactions_csv.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "output/hdf5_io.hpp"

namespace cc {

namespace {

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

constexpr const char* kAxes[3] = {"Fx", "Fy", "Fz"};

}  // namespace

ReactionsCsv::ReactionsCsv(std::string path, bool withContact)
    : path_(std::move(path)), withContact_(withContact) {
  file_ = std::fopen(path_.c_str(), "w");
  if (file_ == nullptr)
    throw OutputError("cannot create CSV file '" + path_ + "': " + std::strerror(errno));
}

ReactionsCsv::~ReactionsCsv() {
  if (file_ != nullptr) std::fclose(file_);
}

std::vector<std::string> ReactionsCsv::columnNames(const StepRecord& step) const {
  std::vector<std::string> names = {"step", "time", "iterations"};
  for (const auto& [set, force] : step.setReactions)
    for (const char* axis : kAxes) names.push_back(set + "_" + axis);
  if (withContact_)
    for (const ContactPairRecord& pair : step.contact)
      for (const char* axis : kAxes) names.push_back("contact_" + pair.name + "_" + axis);
  return names;
}

void ReactionsCsv::appendStep(const StepRecord& step) {
  const std::vector<std::string> names = columnNames(step);
  if (columns_.empty()) {
    columns_ = names;
    std::string header;
    for (const std::string& name : names) header += (header.empty() ? "" : ",") + csvField(name);
    write(header + "\n");
  } else if (names != columns_) {
    throw std::invalid_argument("step " + std::to_string(step.step) +
                                ": node sets or contact pairs differ from the first step, so the "
                                "columns of '" +
                                path_ + "' would not line up");
  }
  std::string row = std::to_string(step.step) + "," + formatNumber(step.time) + "," +
                    std::to_string(step.iterations);
  for (const auto& [set, force] : step.setReactions)
    for (int axis = 0; axis < 3; ++axis) row.append(",").append(formatNumber(force[axis]));
  if (withContact_)
    for (const ContactPairRecord& pair : step.contact)
      for (int axis = 0; axis < 3; ++axis)
        row.append(",").append(formatNumber(pair.totalForce[axis]));
  write(row + "\n");
}

void ReactionsCsv::write(const std::string& text) {
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0)
    throw OutputError("cannot write CSV file '" + path_ + "': " + std::strerror(errno));
}

}  // namespace cc
