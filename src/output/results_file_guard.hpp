// Guarding results files (issue 15): which existing file a run may replace (only a file that
// CovContact wrote, and never one of the run's inputs), the lock that keeps a second writer of
// the same file out before anything is truncated, and saying what a path that cannot be read as
// a results file is instead of HDF5's "unable to open file".
#pragma once

#include <string>
#include <vector>

namespace cc {

// Whether two paths name the same file (the same inode if both exist, else the same canonical
// path).
bool sameFile(const std::string& first, const std::string& second);

// What a run writes at `path`, for the rules and messages of checkReplaceable.
enum class OutputKind { Results, Xdmf, Csv };

// Throws OutputError unless a run may create or replace `path`: it is none of `inputs` (deck,
// included files, mesh, restart file), and if it exists it is empty or a file of `kind` that
// CovContact wrote (a results file by its root attribute `format`; a sidecar by its header).
void checkReplaceable(const std::string& path, OutputKind kind,
                      const std::vector<std::string>& inputs);

// An exclusive advisory lock (flock) on a results file, taken on a descriptor opened without
// truncation, so that a second run writing the same file is refused before it can truncate the
// first one's file. HDF5's own locking is switched off in the writer (it would conflict with this
// lock, and it comes after the truncation). Throws OutputError naming the file if another process
// holds the lock.
class ResultsFileLock {
 public:
  ResultsFileLock() = default;
  explicit ResultsFileLock(const std::string& path);
  ~ResultsFileLock();
  ResultsFileLock(ResultsFileLock&& other) noexcept;
  ResultsFileLock& operator=(ResultsFileLock&& other) noexcept;
  ResultsFileLock(const ResultsFileLock&) = delete;
  ResultsFileLock& operator=(const ResultsFileLock&) = delete;
  bool held() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};

// Whether a run holds the writer's lock on `path` (the file is being written now).
bool beingWritten(const std::string& path);

// Why `path` cannot be opened as an HDF5 file, in words: missing, a directory, a device or FIFO,
// empty, not an HDF5 file (no signature), or an HDF5 file that is truncated or damaged.
std::string unreadableReason(const std::string& path);

}  // namespace cc
