// Guarding results files (issue 15): which existing file a run may replace (only a file that
// CovContact wrote, and never one of the run's inputs), the lock that keeps a second writer of
// the same file out before anything is truncated, the lock that keeps readers of a file in
// progress out of its flushes, and saying what a path that cannot be read as
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

// The lock that keeps a reader of a file in progress from meeting half-written HDF5 metadata
// (issue 15: such a read could leave HDF5 objects open that the library cannot close). The writer
// holds it exclusively from its first change to the file until the flush that makes the file
// consistent again; a reader holds it shared from before it opens the file until after it closes
// it. It is an open-file-description lock (Linux) on one byte far beyond the end of the file:
// independent of the writer's flock, and not dropped when HDF5 closes its own descriptor of the
// same file (classic POSIX record locks would be). A writer waits at most kWriterPatienceSeconds
// for readers and then writes anyway (a stopped reader must not stop a run); a reader waits at most
// kReaderPatienceSeconds for the writer's flush and then throws OutputError.
class ConsistencyLock {
 public:
  static constexpr double kWriterPatienceSeconds = 60;
  static constexpr double kReaderPatienceSeconds = 30;
  ConsistencyLock() = default;
  // Writer: exclusive, on the descriptor `fd` of its ResultsFileLock (-1: a rank without it);
  // not held() if readers kept it for `patience` seconds.
  static ConsistencyLock forWriting(int fd, double patience = kWriterPatienceSeconds);
  // Reader: shared, on a descriptor of its own.
  static ConsistencyLock forReading(const std::string& path,
                                    double patience = kReaderPatienceSeconds);
  ~ConsistencyLock();
  ConsistencyLock(ConsistencyLock&& other) noexcept;
  ConsistencyLock& operator=(ConsistencyLock&& other) noexcept;
  ConsistencyLock(const ConsistencyLock&) = delete;
  ConsistencyLock& operator=(const ConsistencyLock&) = delete;
  bool held() const { return fd_ >= 0; }

 private:
  void release() noexcept;
  int fd_ = -1;
  bool ownsDescriptor_ = false;
};

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
  // Exclusive ConsistencyLock on this descriptor, for one change of the file up to its flush.
  ConsistencyLock beginChange(double patience = ConsistencyLock::kWriterPatienceSeconds) const {
    return ConsistencyLock::forWriting(fd_, patience);
  }

 private:
  int fd_ = -1;
};

// Whether a run holds the writer's lock on `path` (the file is being written now).
bool beingWritten(const std::string& path);

// Why `path` cannot be opened as an HDF5 file, in words: missing, a directory, a device or FIFO,
// empty, not an HDF5 file (no signature), or an HDF5 file that is truncated or damaged.
std::string unreadableReason(const std::string& path);

}  // namespace cc
