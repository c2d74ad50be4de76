// Results-file guards: replaceability rules, the writer's flock, the readers' and writer's
// consistency lock, and descriptions of unreadable paths (see results_file_guard.hpp).
#include "output/results_file_guard.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <utility>

#include "output/hdf5_io.hpp"
#include "output/results_layout.hpp"

namespace cc {

namespace {

namespace fs = std::filesystem;

// The 8-byte HDF5 file signature; it sits at offset 0 or after a user block of 512, 1024, ...
constexpr std::array<unsigned char, 8> kHdf5Signature{0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};

bool hasHdf5Signature(const std::string& path, std::uintmax_t size) {
  std::ifstream stream(path, std::ios::binary);
  for (std::uintmax_t offset = 0; offset + kHdf5Signature.size() <= size;
       offset = offset == 0 ? 512 : 2 * offset) {
    std::array<char, 8> bytes{};
    stream.seekg(static_cast<std::streamoff>(offset));
    if (!stream.read(bytes.data(), bytes.size())) return false;
    if (std::memcmp(bytes.data(), kHdf5Signature.data(), bytes.size()) == 0) return true;
  }
  return false;
}

std::string leadingText(const std::string& path, std::size_t bytes) {
  std::ifstream stream(path, std::ios::binary);
  std::string text(bytes, '\0');
  stream.read(text.data(), static_cast<std::streamsize>(bytes));
  text.resize(static_cast<std::size_t>(stream.gcount()));
  return text;
}

// Whether the existing, non-empty file at `path` was written by CovContact as `kind`.
bool writtenByUs(const std::string& path, OutputKind kind) {
  switch (kind) {
    case OutputKind::Xdmf:
      return leadingText(path, 256).find("<Xdmf ") != std::string::npos;
    case OutputKind::Csv:
      return leadingText(path, 64).rfind("step,time,iterations", 0) == 0;
    case OutputKind::Results:
      break;
  }
  h5::QuietErrors quiet;
  h5::PropertyList access(H5Pcreate(H5P_FILE_ACCESS));
  if (!access.valid() || H5Pset_file_locking(access.get(), false, true) < 0) return false;
  const h5::File file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, access.get()));
  if (!file.valid()) return false;
  try {
    const h5::FileRef ref{file.get(), path};
    return h5::hasAttribute(ref, file.get(), "format") &&
           h5::readStringAttribute(ref, file.get(), "format") == layout::kFormatName;
  } catch (const OutputError&) {
    return false;
  }
}

// Whether another process holds the exclusive flock a ResultsWriter takes on its file.
bool lockedByAWriter(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool locked = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);  // releases the shared lock if it was granted
  return locked;
}

const char* kindName(OutputKind kind) {
  switch (kind) {
    case OutputKind::Results:
      return "results file";
    case OutputKind::Xdmf:
      return "XDMF file";
    case OutputKind::Csv:
      return "CSV file";
  }
  return "file";
}

}  // namespace

bool sameFile(const std::string& first, const std::string& second) {
  std::error_code error;
  if (fs::equivalent(first, second, error)) return true;
  const fs::path a = fs::weakly_canonical(fs::absolute(first, error), error);
  const fs::path b = fs::weakly_canonical(fs::absolute(second, error), error);
  return !a.empty() && a == b;
}

void checkReplaceable(const std::string& path, OutputKind kind,
                      const std::vector<std::string>& inputs) {
  const std::string what = std::string(kindName(kind)) + " '" + path + "'";
  for (const std::string& input : inputs) {
    if (sameFile(path, input))
      throw OutputError("refusing to write " + what + ": it is '" + input +
                        "', an input of this run; choose another results file with -o");
  }
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) return;
  if (fs::is_directory(status)) throw OutputError("cannot write " + what + ": it is a directory");
  if (!fs::is_regular_file(status))
    throw OutputError("refusing to write " + what +
                      ": it is not a regular file (a device, FIFO or socket)");
  if (fs::file_size(path, error) == 0 || error) return;
  if (writtenByUs(path, kind)) return;
  // A file that a run in progress is writing may not have its root attributes on disk yet, and
  // would look foreign: the writer's flock tells (ours is taken only after this check passes).
  if (kind == OutputKind::Results && lockedByAWriter(path))
    throw OutputError("results file '" + path +
                      "' is being written by another process (a run in progress); wait for it "
                      "to finish or choose another results file with -o");
  throw OutputError("refusing to overwrite " + what +
                    ": it exists and was not written by CovContact; remove it or choose "
                    "another results file with -o");
}

ResultsFileLock::ResultsFileLock(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) throw OutputError("cannot open results file '" + path + "': " + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int reason = errno;
    ::close(fd);
    if (reason == EWOULDBLOCK)
      throw OutputError("results file '" + path +
                        "' is being written by another process (a run in progress); wait for it "
                        "to finish or choose another results file with -o");
    throw OutputError("cannot lock results file '" + path + "': " + std::strerror(reason));
  }
  fd_ = fd;
}

ResultsFileLock::~ResultsFileLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the descriptor releases the flock
}

ResultsFileLock::ResultsFileLock(ResultsFileLock&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)) {}

ResultsFileLock& ResultsFileLock::operator=(ResultsFileLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

namespace {

// The locked byte: far beyond the end of any results file, so no reader or writer of the data
// ever touches it (lock ranges may lie beyond the end of a file).
constexpr off_t kConsistencyByte = off_t{1} << 62;

enum class LockOutcome { Granted, Busy, Unsupported };

// The consistency byte as an fcntl lock range of `type` (F_RDLCK, F_WRLCK or F_UNLCK).
struct flock consistencyRange(short type) {
  struct flock range {};
  range.l_type = type;
  range.l_whence = SEEK_SET;
  range.l_start = kConsistencyByte;
  range.l_len = 1;
  return range;
}

// Takes the open-file-description lock of `type` on the consistency byte, polling until it is
// granted or `patience` has passed (Busy). Unsupported: the file system refuses such locks.
LockOutcome takeConsistencyLock(int fd, short type, double patience) {
  struct flock range = consistencyRange(type);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(patience);
  auto pause = std::chrono::microseconds(100);
  for (;;) {
    if (::fcntl(fd, F_OFD_SETLK, &range) == 0) return LockOutcome::Granted;
    if (errno != EAGAIN && errno != EACCES && errno != EINTR) return LockOutcome::Unsupported;
    if (std::chrono::steady_clock::now() >= deadline) return LockOutcome::Busy;
    std::this_thread::sleep_for(pause);
    pause = std::min(2 * pause, std::chrono::microseconds(20000));
  }
}

}  // namespace

ConsistencyLock ConsistencyLock::forWriting(int fd, double patience) {
  ConsistencyLock lock;
  if (fd >= 0 && takeConsistencyLock(fd, F_WRLCK, patience) == LockOutcome::Granted) lock.fd_ = fd;
  return lock;
}

ConsistencyLock ConsistencyLock::forReading(const std::string& path, double patience) {
  ConsistencyLock lock;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return lock;  // opening the file will fail and say why
  const LockOutcome outcome = takeConsistencyLock(fd, F_RDLCK, patience);
  if (outcome != LockOutcome::Granted) {
    ::close(fd);
    if (outcome == LockOutcome::Unsupported) return lock;  // read as before, without the lock
    std::ostringstream message;
    message << "cannot read '" << path << "': the run writing it did not finish a flush in "
            << patience << " s";
    throw OutputError(message.str());
  }
  lock.fd_ = fd;
  lock.ownsDescriptor_ = true;
  return lock;
}

void ConsistencyLock::release() noexcept {
  if (fd_ < 0) return;
  if (ownsDescriptor_) {
    ::close(fd_);  // closing our own description releases its lock
  } else {
    struct flock range = consistencyRange(F_UNLCK);
    ::fcntl(fd_, F_OFD_SETLK, &range);
  }
  fd_ = -1;
  ownsDescriptor_ = false;
}

ConsistencyLock::~ConsistencyLock() {
  release();
}

ConsistencyLock::ConsistencyLock(ConsistencyLock&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      ownsDescriptor_(std::exchange(other.ownsDescriptor_, false)) {}

ConsistencyLock& ConsistencyLock::operator=(ConsistencyLock&& other) noexcept {
  if (this != &other) {
    release();
    fd_ = std::exchange(other.fd_, -1);
    ownsDescriptor_ = std::exchange(other.ownsDescriptor_, false);
  }
  return *this;
}

bool beingWritten(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return false;
  // A shared lock is refused only while a writer holds its exclusive one; release it at once.
  const bool locked = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  return locked;
}

std::string unreadableReason(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) return "it does not exist";
  if (fs::is_directory(status)) return "it is a directory, not a results file";
  if (!fs::is_regular_file(status)) return "it is not a regular file (a device, FIFO or socket)";
  if (::access(path.c_str(), R_OK) != 0) return std::strerror(errno);
  const std::uintmax_t size = fs::file_size(path, error);
  if (size == 0) return "it is empty (0 bytes), not a results file";
  if (!hasHdf5Signature(path, size)) return "it is not an HDF5 file (no HDF5 signature)";
  return "it is an HDF5 file that is truncated or damaged (" + std::to_string(size) + " bytes)";
}

}  // namespace cc
