// HDF5 C API helpers: error capture, group/attribute/dataset creation and reading (see
// hdf5_io.hpp).
#include "output/hdf5_io.hpp"

#include <array>

namespace cc::h5 {

namespace {

// Collects the most specific message on HDF5's error stack (the first one walking downward).
herr_t collectInnermost(unsigned position, const H5E_error2_t* error, void* clientData) {
  auto* message = static_cast<std::string*>(clientData);
  if (position == 0 && error->desc != nullptr) *message = error->desc;
  return 0;
}

hid_t nativeType(double) {
  return H5T_NATIVE_DOUBLE;
}
hid_t nativeType(int) {
  return H5T_NATIVE_INT;
}

template <class Scalar>
Dataset writeArray(FileRef file, hid_t parent, const std::string& name, const Scalar* data,
                   hsize_t rows, hsize_t cols, hid_t fileType) {
  const std::string operation = "writing dataset '" + name + "'";
  const std::array<hsize_t, 2> dims{rows, cols};
  const int rank = cols == 0 ? 1 : 2;
  Space space(check(H5Screate_simple(rank, dims.data(), nullptr), file.path, operation));
  Dataset dataset(check(H5Dcreate2(parent, name.c_str(), fileType, space.get(), H5P_DEFAULT,
                                   H5P_DEFAULT, H5P_DEFAULT),
                        file.path, operation));
  if (rows == 0 || (rank == 2 && cols == 0)) return dataset;  // nothing to transfer when empty
  // The memory holds the whole array in the file's shape: the same selection picks the rows.
  Space memory(check(H5Screate_simple(rank, dims.data(), nullptr), file.path, operation));
  const hid_t transfer = selectShare(file, space.get(), rows, operation);
  selectShare(file, memory.get(), rows, operation);
  checkStatus(
      H5Dwrite(dataset.get(), nativeType(Scalar{}), memory.get(), space.get(), transfer, data),
      file.path, operation);
  return dataset;
}

Attribute createAttribute(FileRef file, hid_t object, const std::string& name, hid_t type,
                          hid_t space) {
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  return Attribute(check(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
                         file.path, "creating attribute '" + name + "'"));
}

void writeScalarAttribute(FileRef file, hid_t object, const std::string& name, hid_t fileType,
                          hid_t memoryType, const void* value) {
  Space space(check(H5Screate(H5S_SCALAR), file.path, "creating attribute '" + name + "'"));
  Attribute attribute = createAttribute(file, object, name, fileType, space.get());
  checkStatus(H5Awrite(attribute.get(), memoryType, value), file.path,
              "writing attribute '" + name + "'");
}

}  // namespace

QuietErrors::QuietErrors() {
  H5Eget_auto2(H5E_DEFAULT, &previousHandler_, &previousData_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

QuietErrors::~QuietErrors() {
  H5Eset_auto2(H5E_DEFAULT, previousHandler_, previousData_);
}

void fail(const std::string& file, const std::string& operation) {
  std::string detail;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collectInnermost, &detail);
  H5Eclear2(H5E_DEFAULT);
  std::string message = "HDF5 error " + operation + " in '" + file + "'";
  if (!detail.empty()) message += ": " + detail;
  throw OutputError(message);
}

hid_t check(hid_t id, const std::string& file, const std::string& operation) {
  if (id < 0) fail(file, operation);
  return id;
}

void checkStatus(herr_t status, const std::string& file, const std::string& operation) {
  if (status < 0) fail(file, operation);
}

hid_t selectShare(FileRef file, hid_t space, hsize_t rows, const std::string& operation) {
  if (file.share == nullptr || file.share->parts == 1) {
    checkStatus(H5Sselect_all(space), file.path, operation);
    return H5P_DEFAULT;
  }
  const auto part = static_cast<hsize_t>(file.share->part);
  const auto parts = static_cast<hsize_t>(file.share->parts);
  const hsize_t begin = rows * part / parts, end = rows * (part + 1) / parts;
  if (begin == end) {
    checkStatus(H5Sselect_none(space), file.path, operation);
  } else {
    std::array<hsize_t, 2> start{begin, 0}, count{end - begin, 0};
    if (H5Sget_simple_extent_ndims(space) == 2) {
      H5Sget_simple_extent_dims(space, count.data(), nullptr);  // all columns
      count[0] = end - begin;
    }
    checkStatus(
        H5Sselect_hyperslab(space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr),
        file.path, operation);
  }
  return file.share->transfer;
}

bool exists(FileRef file, hid_t parent, const std::string& name) {
  const htri_t found = H5Lexists(parent, name.c_str(), H5P_DEFAULT);
  if (found < 0) fail(file.path, "looking up '" + name + "'");
  return found > 0;
}

Group createGroup(FileRef file, hid_t parent, const std::string& name) {
  // No creation-order index: one index less to update per step, which made writing faster and
  // files killed inside a flush no more fragile (measured, docs/output-format.md). Orders that
  // matter are explicit (zero-padded step names, the blocks' "names" attribute).
  return Group(check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                     file.path, "creating group '" + name + "'"));
}

Group openGroup(FileRef file, hid_t parent, const std::string& name) {
  return Group(check(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), file.path,
                     "opening group '" + name + "'"));
}

std::vector<std::string> childNames(FileRef file, hid_t group) {
  H5G_info_t info;
  checkStatus(H5Gget_info(group, &info), file.path, "listing a group");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (length < 0) fail(file.path, "listing a group");
    std::string name(static_cast<size_t>(length), '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size() + 1,
                       H5P_DEFAULT);
    names.push_back(std::move(name));
  }
  return names;
}

Type variableString() {
  Type type(H5Tcopy(H5T_C_S1));
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  return type;
}

void writeAttribute(FileRef file, hid_t object, const std::string& name, double value) {
  writeScalarAttribute(file, object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void writeAttribute(FileRef file, hid_t object, const std::string& name, int value) {
  writeScalarAttribute(file, object, name, H5T_STD_I32LE, H5T_NATIVE_INT, &value);
}

void writeAttribute(FileRef file, hid_t object, const std::string& name, const std::string& value) {
  // Variable-length strings keep even a long deck text out of the 64 KiB attribute header limit.
  const Type type = variableString();
  const char* text = value.c_str();
  writeScalarAttribute(file, object, name, type.get(), type.get(), &text);
}

void writeAttribute(FileRef file, hid_t object, const std::string& name,
                    const std::vector<std::string>& values) {
  const Type type = variableString();
  const hsize_t count = values.size();
  Space space(
      check(H5Screate_simple(1, &count, nullptr), file.path, "creating attribute '" + name + "'"));
  Attribute attribute = createAttribute(file, object, name, type.get(), space.get());
  std::vector<const char*> texts;
  for (const std::string& value : values) texts.push_back(value.c_str());
  if (texts.empty()) return;
  checkStatus(H5Awrite(attribute.get(), type.get(), texts.data()), file.path,
              "writing attribute '" + name + "'");
}

bool hasAttribute(FileRef file, hid_t object, const std::string& name) {
  const htri_t found = H5Aexists(object, name.c_str());
  if (found < 0) fail(file.path, "looking up attribute '" + name + "'");
  return found > 0;
}

double readNumberAttribute(FileRef file, hid_t object, const std::string& name) {
  Attribute attribute(check(H5Aopen(object, name.c_str(), H5P_DEFAULT), file.path,
                            "opening attribute '" + name + "'"));
  double value = 0;
  checkStatus(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value), file.path,
              "reading attribute '" + name + "'");
  return value;
}

std::vector<std::string> readStringListAttribute(FileRef file, hid_t object,
                                                 const std::string& name) {
  const std::string operation = "reading attribute '" + name + "'";
  Attribute attribute(check(H5Aopen(object, name.c_str(), H5P_DEFAULT), file.path, operation));
  Space space(check(H5Aget_space(attribute.get()), file.path, operation));
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) fail(file.path, operation);
  Type storedType(check(H5Aget_type(attribute.get()), file.path, operation));
  if (H5Tget_class(storedType.get()) != H5T_STRING || H5Tis_variable_str(storedType.get()) <= 0)
    throw OutputError("attribute '" + name + "' in '" + file.path +
                      "' is not a variable-length string");
  const Type type = variableString();
  std::vector<char*> texts(static_cast<size_t>(count), nullptr);
  if (count > 0)
    checkStatus(H5Aread(attribute.get(), type.get(), texts.data()), file.path, operation);
  std::vector<std::string> values;
  for (char* text : texts) values.emplace_back(text != nullptr ? text : "");
  if (count > 0) H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, texts.data());
  return values;
}

std::string readStringAttribute(FileRef file, hid_t object, const std::string& name) {
  std::vector<std::string> values = readStringListAttribute(file, object, name);
  if (values.size() != 1)
    throw OutputError("attribute '" + name + "' in '" + file.path + "' is not a single string");
  return values.front();
}

Dataset writeDoubles(FileRef file, hid_t parent, const std::string& name, const double* data,
                     hsize_t rows, hsize_t cols) {
  return writeArray(file, parent, name, data, rows, cols, H5T_IEEE_F64LE);
}

Dataset writeInts(FileRef file, hid_t parent, const std::string& name, const int* data,
                  hsize_t rows, hsize_t cols) {
  return writeArray(file, parent, name, data, rows, cols, H5T_STD_I32LE);
}

Eigen::MatrixXd readDoubles(FileRef file, hid_t parent, const std::string& path) {
  const std::string operation = "reading dataset '" + path + "'";
  Dataset dataset(check(H5Dopen2(parent, path.c_str(), H5P_DEFAULT), file.path, operation));
  Space space(check(H5Dget_space(dataset.get()), file.path, operation));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank != 1 && rank != 2)
    throw OutputError("dataset '" + path + "' in '" + file.path + "' has rank " +
                      std::to_string(rank) + " (expected 1 or 2)");
  std::array<hsize_t, 2> dims{0, 1};
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor values(static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]));
  if (values.size() > 0)
    checkStatus(
        H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
        file.path, operation);
  return values;
}

}  // namespace cc::h5
