// Reference errors as a printed table and as the /verification group of the results file.
#include "verification/reference_report.hpp"

#include <fmt/format.h>

#include <cmath>

#include "output/hdf5_io.hpp"
#include "output/results_file_guard.hpp"

namespace cc::verification {

namespace {

std::string relativeText(double relative) {
  return std::isnan(relative) ? std::string("-") : fmt::format("{:+.3g}%", 100 * relative);
}

std::string label(const ReferenceResult& result) {
  return result.kind == "analytic" ? fmt::format("{} ({})", result.quantity, result.analytic)
                                   : fmt::format("{} ({})", result.quantity, result.kind);
}

void writeResult(h5::FileRef file, hid_t parent, const std::string& name,
                 const ReferenceResult& result) {
  const h5::Group group = h5::createGroup(file, parent, name);
  const hid_t id = group.get();
  h5::writeAttribute(file, id, "quantity", result.quantity);
  h5::writeAttribute(file, id, "kind", result.kind);
  h5::writeAttribute(file, id, "analytic", result.analytic);
  h5::writeAttribute(file, id, "parameters", result.parameters);
  h5::writeAttribute(file, id, "location", result.location);
  const bool sampled = !result.samples.empty();
  const double nan = std::nan("");
  h5::writeAttribute(file, id, "time", sampled ? result.samples.back().time : nan);
  h5::writeAttribute(file, id, "measured", sampled ? result.samples.back().measured : nan);
  h5::writeAttribute(file, id, "reference", sampled ? result.samples.back().reference : nan);
  h5::writeAttribute(file, id, "error", result.error);
  h5::writeAttribute(file, id, "relative_error", result.relativeError);
  h5::writeAttribute(file, id, "max_error", result.maxError);
  h5::writeAttribute(file, id, "max_relative_error", result.maxRelativeError);
  const auto rows = static_cast<hsize_t>(result.samples.size());
  std::vector<double> time, measured, reference;
  for (const ReferenceSample& sample : result.samples) {
    time.push_back(sample.time);
    measured.push_back(sample.measured);
    reference.push_back(sample.reference);
  }
  h5::writeDoubles(file, id, "time", time.data(), rows, 0);
  h5::writeDoubles(file, id, "measured", measured.data(), rows, 0);
  h5::writeDoubles(file, id, "reference", reference.data(), rows, 0);
}

}  // namespace

std::string formatReferenceErrors(const std::vector<ReferenceResult>& results,
                                  const RunCost& cost) {
  std::string text = fmt::format("{:<52} {:>12} {:>12} {:>10} {:>10}\n", "reference", "measured",
                                 "reference", "error", "max error");
  for (const ReferenceResult& result : results) {
    if (result.samples.empty()) {
      text += fmt::format("{:<52} not compared: no step in the reference's range\n", label(result));
      continue;
    }
    const ReferenceSample& last = result.samples.back();
    const std::string error = std::isnan(result.relativeError)
                                  ? fmt::format("{:+.3g}", result.error)
                                  : relativeText(result.relativeError);
    const std::string maxError = std::isnan(result.maxRelativeError)
                                     ? fmt::format("{:.3g}", result.maxError)
                                     : relativeText(result.maxRelativeError);
    text += fmt::format("{:<52} {:>12.6g} {:>12.6g} {:>10} {:>10}\n", label(result), last.measured,
                        last.reference, error, maxError);
  }
  text += fmt::format("cost: {:.2f} s wall time, {} Newton iterations, {} steps\n",
                      cost.wallSeconds, cost.newtonIterations, cost.steps);
  return text;
}

void writeReferenceErrors(const std::string& h5Path, const std::vector<ReferenceResult>& results,
                          const RunCost& cost) {
  h5::QuietErrors quiet;
  // The writer's lock (not HDF5's, which would conflict with it): no other run may be writing.
  const ResultsFileLock lock(h5Path);
  const h5::PropertyList access(
      h5::check(H5Pcreate(H5P_FILE_ACCESS), h5Path, "opening the file to add /verification"));
  h5::checkStatus(H5Pset_file_locking(access.get(), false, true), h5Path,
                  "opening the file to add /verification");
  const h5::File file(h5::check(H5Fopen(h5Path.c_str(), H5F_ACC_RDWR, access.get()), h5Path,
                                "opening the file to add /verification"));
  const h5::FileRef ref{file.get(), h5Path};
  const h5::Group group = h5::createGroup(ref, file.get(), "verification");
  h5::writeAttribute(ref, group.get(), "wall_seconds", cost.wallSeconds);
  h5::writeAttribute(ref, group.get(), "newton_iterations", cost.newtonIterations);
  h5::writeAttribute(ref, group.get(), "steps", cost.steps);
  for (std::size_t k = 0; k < results.size(); ++k) {
    writeResult(ref, group.get(), fmt::format("reference_{}", k + 1), results[k]);
  }
}

}  // namespace cc::verification
