// Error types shared by all modules and the process exit codes they map to.
// InputError: the user's deck or mesh is wrong (always names file:line and what was expected).
// StepFailure: one load step could not be solved (the stepper cuts back; carries the culprit).
// RunAborted: the run stops (signal, cut-back limit); converged steps stay on disk.
#pragma once

#include <stdexcept>
#include <string>

#include "common/source_location.hpp"

namespace cc {

// Exit codes of the `covcontact` command; documented in `covcontact --help`.
enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 1,        // bad command line
  kExitInput = 2,        // invalid deck, mesh or include file
  kExitDiverged = 3,     // a step failed after all cut-backs; converged steps are on disk
  kExitInterrupted = 4,  // SIGINT/SIGTERM: stopped cleanly after the current iteration
  kExitMismatch = 5,     // `compare`: results differ from the reference
  kExitIo = 6,           // output file could not be written / reference not readable
  kExitSingular = 7,     // singular system (e.g. unconstrained rigid-body motion)
  kExitOutOfMemory = 8,  // the model or its factor did not fit in memory; converged steps kept
  kExitInternal = 70,    // a bug: please report
};

class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& message);
  const SourceLocation& where() const { return where_; }
  const std::string& bareMessage() const { return bare_; }

 private:
  SourceLocation where_;
  std::string bare_;
};

// Why a step (or one Newton iteration of it) failed; the load stepper reacts by cutting back.
enum class FailureKind {
  NotFinite,          // NaN or Inf in a residual, tangent or solution
  InvertedElement,    // det J <= 0 at an integration point
  ProjectionFailure,  // a contact point could not be projected
  Diverged,           // residual grew / no convergence within the iteration limit
  SingularSystem,     // the linear solver found the system singular
  LocalIteration,     // element-level iteration (e.g. EAS) did not converge
};

const char* toString(FailureKind kind);

class StepFailure : public std::runtime_error {
 public:
  StepFailure(FailureKind kind, const std::string& message)
      : std::runtime_error(message), kind_(kind) {}
  FailureKind kind() const { return kind_; }

 private:
  FailureKind kind_;
};

// Memory ran out for something the message names with its size (a factor, the model): a limit of
// the machine, not a step that a smaller increment could fix, so the run stops (kExitOutOfMemory).
class OutOfMemory : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace cc
