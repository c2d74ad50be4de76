// Reading results files: path lookups that tolerate missing components, typed reads, the tables.
#include "output/results_reader.hpp"

#include <filesystem>

#include "output/results_file_guard.hpp"
#include "output/results_layout.hpp"

namespace cc {

namespace {

template <class Row>
std::vector<Row> readTable(h5::FileRef file, const char* name, hid_t rowType) {
  const std::string operation = std::string("reading table '") + name + "'";
  h5::Dataset table(h5::check(H5Dopen2(file.id, name, H5P_DEFAULT), file.path, operation));
  h5::Space space(h5::check(H5Dget_space(table.get()), file.path, operation));
  const hssize_t rows = H5Sget_simple_extent_npoints(space.get());
  if (rows < 0) h5::fail(file.path, operation);
  std::vector<Row> values(static_cast<size_t>(rows));
  if (rows > 0)
    h5::checkStatus(H5Dread(table.get(), rowType, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
                    file.path, operation);
  return values;
}

}  // namespace

ResultsReader::ResultsReader(const std::string& path) : path_(path) {
  // Not a regular file: say so before HDF5 tries (opening a FIFO would block).
  std::error_code error;
  if (!std::filesystem::is_regular_file(path_, error))
    throw OutputError("cannot read '" + path_ + "' as a results file: " + unreadableReason(path_));
  consistency_ = ConsistencyLock::forReading(path_);
  h5::QuietErrors quiet;
  h5::PropertyList access(h5::check(H5Pcreate(H5P_FILE_ACCESS), path_, "opening the file"));
  // Readers never modify the file, so they need no lock; this lets us read a run in progress.
  h5::checkStatus(H5Pset_file_locking(access.get(), false, true), path_, "opening the file");
  file_ = h5::File(H5Fopen(path_.c_str(), H5F_ACC_RDONLY, access.get()));
  if (!file_.valid()) {
    // Say what the path is instead of HDF5's "unable to open file".
    std::string why = unreadableReason(path_);
    if (beingWritten(path_)) why += "; a run is writing it right now";
    throw OutputError("cannot read '" + path_ + "' as a results file: " + why);
  }
  if (!h5::hasAttribute(ref(), file_.get(), "format") ||
      h5::readStringAttribute(ref(), file_.get(), "format") != layout::kFormatName)
    throw OutputError("'" + path_ + "' is an HDF5 file but not a CovContact results file");
}

H5I_type_t ResultsReader::objectType(const std::string& path) const {
  h5::QuietErrors quiet;
  // Check every prefix: H5Oopen on a path through a missing group is an error, not "absent".
  for (size_t slash = path.find('/', 1);; slash = path.find('/', slash + 1)) {
    const std::string prefix = path.substr(0, slash);
    if (H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) return H5I_BADID;
    if (slash == std::string::npos) break;
  }
  const hid_t object = H5Oopen(file_.get(), path.c_str(), H5P_DEFAULT);
  if (object < 0) return H5I_BADID;
  const H5I_type_t type = H5Iget_type(object);
  H5Oclose(object);
  return type;
}

bool ResultsReader::hasDataset(const std::string& path) const {
  return objectType(path) == H5I_DATASET;
}

bool ResultsReader::hasGroup(const std::string& path) const {
  return path == "/" || objectType(path) == H5I_GROUP;
}

std::vector<std::string> ResultsReader::children(const std::string& group) const {
  if (!hasGroup(group)) return {};
  h5::QuietErrors quiet;
  const h5::Group opened = h5::openGroup(ref(), file_.get(), group);
  return h5::childNames(ref(), opened.get());
}

Eigen::MatrixXd ResultsReader::readMatrix(const std::string& path) const {
  h5::QuietErrors quiet;
  return h5::readDoubles(ref(), file_.get(), path);
}

bool ResultsReader::hasAttribute(const std::string& object, const std::string& name) const {
  h5::QuietErrors quiet;
  return objectType(object) != H5I_BADID &&
         H5Aexists_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

double ResultsReader::numberAttribute(const std::string& object, const std::string& name) const {
  h5::QuietErrors quiet;
  const h5::Handle<H5Oclose> opened(h5::check(H5Oopen(file_.get(), object.c_str(), H5P_DEFAULT),
                                              path_, "opening '" + object + "'"));
  return h5::readNumberAttribute(ref(), opened.get(), name);
}

std::string ResultsReader::stringAttribute(const std::string& object,
                                           const std::string& name) const {
  h5::QuietErrors quiet;
  const h5::Handle<H5Oclose> opened(h5::check(H5Oopen(file_.get(), object.c_str(), H5P_DEFAULT),
                                              path_, "opening '" + object + "'"));
  return h5::readStringAttribute(ref(), opened.get(), name);
}

std::vector<std::string> ResultsReader::stringListAttribute(const std::string& object,
                                                            const std::string& name) const {
  h5::QuietErrors quiet;
  const h5::Handle<H5Oclose> opened(h5::check(H5Oopen(file_.get(), object.c_str(), H5P_DEFAULT),
                                              path_, "opening '" + object + "'"));
  return h5::readStringListAttribute(ref(), opened.get(), name);
}

std::vector<StepHeader> ResultsReader::steps() const {
  std::vector<StepHeader> headers;
  for (const std::string& name : children(layout::kStepsGroup)) {
    StepHeader header;
    header.group = std::string(layout::kStepsGroup) + "/" + name;
    header.step = static_cast<int>(numberAttribute(header.group, "step"));
    header.time = numberAttribute(header.group, "time");
    header.iterations = static_cast<int>(numberAttribute(header.group, "iterations"));
    header.cutbacks = static_cast<int>(numberAttribute(header.group, "cutbacks"));
    headers.push_back(std::move(header));
  }
  return headers;
}

std::vector<IterationRecord> ResultsReader::convergence() const {
  h5::QuietErrors quiet;
  const h5::Type rowType = layout::convergenceRowType();
  std::vector<IterationRecord> records;
  for (const layout::ConvergenceRow& row :
       readTable<layout::ConvergenceRow>(ref(), layout::kConvergence, rowType.get()))
    records.push_back({row.step, row.attempt, row.iteration, row.time, row.residual,
                       row.relativeResidual, row.energy, row.relativeEnergy, row.wallSeconds});
  return records;
}

std::vector<CutbackRecord> ResultsReader::cutbacks() const {
  h5::QuietErrors quiet;
  std::vector<CutbackRecord> records;
  if (!storesVariableLengthReason()) {
    const h5::Type rowType = layout::cutbackRowType();
    for (const layout::CutbackRow& row :
         readTable<layout::CutbackRow>(ref(), layout::kCutbacks, rowType.get()))
      records.push_back({row.step, row.time, row.newDt, row.reason});
    return records;
  }
  const h5::Type rowType = layout::cutbackRowTypeV1();
  std::vector<layout::CutbackRowV1> rows =
      readTable<layout::CutbackRowV1>(ref(), layout::kCutbacks, rowType.get());
  for (const layout::CutbackRowV1& row : rows)
    records.push_back({row.step, row.time, row.newDt, row.reason != nullptr ? row.reason : ""});
  if (!rows.empty()) {
    const hsize_t count = rows.size();
    h5::Space space(H5Screate_simple(1, &count, nullptr));
    H5Dvlen_reclaim(rowType.get(), space.get(), H5P_DEFAULT, rows.data());
  }
  return records;
}

// Format version 1 stored the cut-back reason as a variable-length string.
bool ResultsReader::storesVariableLengthReason() const {
  const std::string operation = "reading table '" + std::string(layout::kCutbacks) + "'";
  h5::Dataset table(
      h5::check(H5Dopen2(file_.get(), layout::kCutbacks, H5P_DEFAULT), path_, operation));
  h5::Type type(h5::check(H5Dget_type(table.get()), path_, operation));
  const int member = H5Tget_member_index(type.get(), "reason");
  if (member < 0) h5::fail(path_, operation);
  h5::Type reason(
      h5::check(H5Tget_member_type(type.get(), static_cast<unsigned>(member)), path_, operation));
  return H5Tis_variable_str(reason.get()) > 0;
}

}  // namespace cc
