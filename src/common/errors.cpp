// Formatting of locations and errors shared by all modules.
#include "common/errors.hpp"

#include <fmt/format.h>

namespace cc {

std::string SourceLocation::str() const {
  if (file.empty()) return "<unknown>";
  if (line <= 0) return file;
  if (column <= 0) return fmt::format("{}:{}", file, line);
  return fmt::format("{}:{}:{}", file, line, column);
}

InputError::InputError(SourceLocation where, const std::string& message)
    : std::runtime_error(fmt::format("{}: error: {}", where.str(), message)),
      where_(std::move(where)),
      bare_(message) {}

const char* toString(FailureKind kind) {
  switch (kind) {
    case FailureKind::NotFinite:
      return "not finite (NaN/Inf)";
    case FailureKind::InvertedElement:
      return "inverted element";
    case FailureKind::ProjectionFailure:
      return "contact projection failure";
    case FailureKind::Diverged:
      return "diverged";
    case FailureKind::SingularSystem:
      return "singular system";
    case FailureKind::LocalIteration:
      return "element-level iteration failed";
  }
  return "unknown";
}

}  // namespace cc
