// ResultsReader: read-only access to a results file written by ResultsWriter (step list, datasets
// by path, attributes, convergence and cut-back tables), for `covcontact compare`, tests and tools.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "output/hdf5_io.hpp"
#include "output/results_file_guard.hpp"
#include "records/result_records.hpp"

namespace cc {

struct StepHeader {
  int step = 0;
  double time = 0;
  int iterations = 0;
  int cutbacks = 0;
  std::string group;  // "/steps/000001"
};

class ResultsReader {
 public:
  // Opens read-only without taking HDF5's file lock, so a file still being written can be read
  // (up to its last flushed step): the reader holds a shared ConsistencyLock from before it opens
  // the file until it is destroyed, so the writer cannot change the file under it. Throws
  // OutputError naming the file if it is not our format.
  explicit ResultsReader(const std::string& path);

  const std::string& path() const { return path_; }
  std::vector<StepHeader> steps() const;

  // Absolute paths, e.g. "/steps/000003/contact/pair1/total_force".
  bool hasDataset(const std::string& path) const;
  bool hasGroup(const std::string& path) const;
  std::vector<std::string> children(const std::string& group) const;  // empty if no such group
  Eigen::MatrixXd readMatrix(const std::string& path) const;          // rank 1 gives one column

  bool hasAttribute(const std::string& object, const std::string& name) const;
  double numberAttribute(const std::string& object, const std::string& name) const;
  std::string stringAttribute(const std::string& object, const std::string& name) const;
  std::vector<std::string> stringListAttribute(const std::string& object,
                                               const std::string& name) const;

  std::vector<IterationRecord> convergence() const;
  std::vector<CutbackRecord> cutbacks() const;

 private:
  h5::FileRef ref() const { return {file_.get(), path_}; }
  bool storesVariableLengthReason() const;
  // H5I type of the object at `path`, or H5I_BADID if some component of it does not exist.
  H5I_type_t objectType(const std::string& path) const;

  std::string path_;
  ConsistencyLock consistency_;  // declared before file_: released after the file is closed
  h5::File file_;
};

}  // namespace cc
