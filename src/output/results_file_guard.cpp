// Results-file guards: replaceability rules, the writer's flock, and descriptions of unreadable
// paths (see results_file_guard.hpp).
#include "output/results_file_guard.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
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
