// Thin RAII layer over the HDF5 C API shared by the results writer and reader: owning handles for
// hid_t, error capture into OutputError (naming file and operation), and typed dataset/attribute
// I/O.
#pragma once

#include <hdf5.h>

#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace cc {

// Any failure to create, write or read a results file (or its XDMF/CSV sidecars). The message
// always names the file and the operation; the app maps it to kExitIo.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace h5 {

// Owns one HDF5 identifier and closes it with the matching H5?close function.
template <herr_t (*Close)(hid_t)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
    }
    return *this;
  }
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes now and reports whether HDF5 accepted the close (needed for files: errors surface here).
  herr_t close() { return id_ >= 0 ? Close(std::exchange(id_, H5I_INVALID_HID)) : 0; }
  void reset() { close(); }

 private:
  hid_t id_ = H5I_INVALID_HID;
};

using File = Handle<H5Fclose>;
using Group = Handle<H5Gclose>;
using Dataset = Handle<H5Dclose>;
using Space = Handle<H5Sclose>;
using Type = Handle<H5Tclose>;
using Attribute = Handle<H5Aclose>;
using PropertyList = Handle<H5Pclose>;

// Switches off HDF5's automatic error-stack printing for its lifetime (we report errors ourselves
// through OutputError) and restores the previous handler afterwards.
class QuietErrors {
 public:
  QuietErrors();
  ~QuietErrors();
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t previousHandler_ = nullptr;
  void* previousData_ = nullptr;
};

// Throws OutputError("<operation> in '<file>': <HDF5's innermost message>").
[[noreturn]] void fail(const std::string& file, const std::string& operation);
// Returns `id` if it is valid, else fail(); wraps every hid_t-returning call.
hid_t check(hid_t id, const std::string& file, const std::string& operation);
void checkStatus(herr_t status, const std::string& file, const std::string& operation);

// How the processes of a run on several processes share the writing of one file that they all
// opened collectively (MPI-IO): every process makes the same calls with the same data, and part
// `part` of `parts` writes rows [part * n / parts, (part + 1) * n / parts) of every array with
// the `transfer` property list (collective transfers). One process: part 0 of 1, which writes
// everything with the default transfer.
struct WriteShare {
  int part = 0;
  int parts = 1;
  hid_t transfer = H5P_DEFAULT;
};

// A file handle together with the path used in error messages, and the share of the writing
// this process does (none: it writes everything).
struct FileRef {
  hid_t id;
  const std::string& path;
  const WriteShare* share = nullptr;
};

// Selects this process's rows [begin, end) of the first dimension in `space` (all of them
// without a share, none for an empty share) and returns the transfer property list to use.
hid_t selectShare(FileRef file, hid_t space, hsize_t rows, const std::string& operation);

bool exists(FileRef file, hid_t parent, const std::string& name);
Group createGroup(FileRef file, hid_t parent, const std::string& name);
Group openGroup(FileRef file, hid_t parent, const std::string& name);
// Names of a group's direct children in name order.
std::vector<std::string> childNames(FileRef file, hid_t group);

Type variableString();  // UTF-8, variable length

void writeAttribute(FileRef file, hid_t object, const std::string& name, double value);
void writeAttribute(FileRef file, hid_t object, const std::string& name, int value);
void writeAttribute(FileRef file, hid_t object, const std::string& name, const std::string& value);
void writeAttribute(FileRef file, hid_t object, const std::string& name,
                    const std::vector<std::string>& values);

bool hasAttribute(FileRef file, hid_t object, const std::string& name);
double readNumberAttribute(FileRef file, hid_t object, const std::string& name);
std::string readStringAttribute(FileRef file, hid_t object, const std::string& name);
std::vector<std::string> readStringListAttribute(FileRef file, hid_t object,
                                                 const std::string& name);

// Writes a rows x cols dataset (rank 1 if cols == 0) from row-major memory. A column-major Eigen
// 3 x N matrix is row-major N x 3 in memory, which is why callers can pass .data() directly.
Dataset writeDoubles(FileRef file, hid_t parent, const std::string& name, const double* data,
                     hsize_t rows, hsize_t cols);
Dataset writeInts(FileRef file, hid_t parent, const std::string& name, const int* data,
                  hsize_t rows, hsize_t cols);

// Reads a rank-1 or rank-2 numeric dataset as doubles (rank 1 gives one column).
Eigen::MatrixXd readDoubles(FileRef file, hid_t parent, const std::string& path);

}  // namespace h5
}  // namespace cc
