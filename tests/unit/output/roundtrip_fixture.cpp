// Writes the shared round-trip run and its expected values (JSON), and raw C API read helpers.
#include "roundtrip_fixture.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

namespace cc::test {

namespace {

namespace fs = std::filesystem;

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

// Rows of a column-major 3 x N (or 6 x E) matrix, i.e. the N x 3 table as stored in the file.
template <class Matrix>
std::string columnsAsRows(const Matrix& matrix) {
  std::string out = "[";
  for (Eigen::Index col = 0; col < matrix.cols(); ++col) {
    out += col == 0 ? "[" : ",[";
    for (Eigen::Index row = 0; row < matrix.rows(); ++row)
      out.append(row == 0 ? "" : ",").append(number(static_cast<double>(matrix(row, col))));
    out += "]";
  }
  return out + "]";
}

template <class Vector>
std::string list(const Vector& vector) {
  std::string out = "[";
  for (Eigen::Index i = 0; i < vector.size(); ++i)
    out.append(i == 0 ? "" : ",").append(number(static_cast<double>(vector(i))));
  return out + "]";
}

std::string contactJson(const ContactPairRecord& pair) {
  const Eigen::VectorXi slaveNodes = Eigen::Map<const Eigen::VectorXi>(
      pair.slaveNodes.data(), static_cast<Eigen::Index>(pair.slaveNodes.size()));
  return "{\"position\":" + columnsAsRows(pair.position) + ",\"gap\":" + list(pair.gap) +
         ",\"normal_traction\":" + list(pair.normalTraction) +
         ",\"tangential_traction\":" + columnsAsRows(pair.tangentialTraction) +
         ",\"state\":" + list(pair.state) + ",\"slip_increment\":" + list(pair.slipIncrement) +
         ",\"accumulated_slip\":" + list(pair.accumulatedSlip) +
         ",\"weight\":" + list(pair.weight) + ",\"edge_share\":" + list(pair.edgeShare) +
         ",\"total_force\":" + list(pair.totalForce) + ",\"slave_nodes\":" + list(slaveNodes) +
         ",\"slave_nodal_force\":" + columnsAsRows(pair.slaveNodalForce) + "}";
}

std::string stepJson(int step) {
  SyntheticStep data;
  roundTripStep(step, data);
  const StepRecord& record = data.record;
  std::string names = "[", forces = "[";
  for (const auto& [name, force] : record.setReactions) {
    names.append(names.size() > 1 ? "," : "").append(quoted(name));
    forces.append(forces.size() > 1 ? "," : "").append(list(force));
  }
  std::string contact = "{";
  for (const ContactPairRecord& pair : record.contact)
    contact.append(contact.size() > 1 ? "," : "")
        .append(quoted(pair.name) + ":" + contactJson(pair));
  return "{\"step\":" + std::to_string(step) + ",\"time\":" + number(record.time) +
         ",\"iterations\":" + std::to_string(record.iterations) +
         ",\"cutbacks\":" + std::to_string(record.cutbacks) +
         ",\"displacement\":" + columnsAsRows(data.displacement) +
         ",\"reaction\":" + columnsAsRows(data.reaction) +
         ",\"stress\":" + columnsAsRows(data.stress) + ",\"set_reaction_names\":" + names +
         "],\"set_reactions\":" + forces + "],\"contact\":" + contact + "}}";
}

std::string expectedJson(const RoundTripRun& run, const RunInfo& info) {
  std::string json = "{\"h5\":" + quoted(run.h5Path) + ",\"xdmf\":" + quoted(run.xdmfPath) +
                     ",\"csv\":" + quoted(run.csvPath) + ",\"deck_text\":" + quoted(info.deckText) +
                     ",\"command_line\":" + quoted(info.commandLine) +
                     ",\"coordinates\":" + columnsAsRows(run.mesh.mesh.coordinates) +
                     ",\"steps\":[";
  for (int step = 1; step <= kRoundTripSteps; ++step)
    json += (step > 1 ? "," : "") + stepJson(step);
  json += "],\"convergence\":[";
  for (size_t i = 0; i < run.iterations.size(); ++i) {
    const IterationRecord& r = run.iterations[i];
    json += (i > 0 ? ",[" : "[") + std::to_string(r.step) + "," + std::to_string(r.attempt) + "," +
            std::to_string(r.iteration) + "," + number(r.time) + "," + number(r.residualNorm) +
            "," + number(r.relativeResidual) + "," + number(r.energy) + "," +
            number(r.relativeEnergy) + "," + number(r.wallSeconds) + "]";
  }
  json += "],\"placements\":{";
  for (size_t i = 0; i < run.mesh.placements.size(); ++i) {
    const BlockPlacement& placement = run.mesh.placements[i];
    json += (i > 0 ? "," : "") + quoted(placement.block) +
            ":{\"origin\":" + list(placement.origin) +
            ",\"edges\":" + columnsAsRows(placement.edges) + "}";
  }
  return json + "}}\n";
}

std::unique_ptr<RoundTripRun> writeRoundTrip() {
  auto run = std::make_unique<RoundTripRun>();
  const char* fixed = std::getenv("COVCONTACT_OUTPUT_TEST_DIR");
  const fs::path directory =
      fixed != nullptr
          ? fs::path(fixed)
          : fs::temp_directory_path() / ("covcontact_output_" + std::to_string(::getpid()));
  fs::create_directories(directory);
  run->directory = fs::absolute(directory).string();
  run->h5Path = run->directory + "/roundtrip.h5";
  run->xdmfPath = run->directory + "/roundtrip.xdmf";
  run->csvPath = run->directory + "/roundtrip_reactions.csv";
  run->jsonPath = run->directory + "/roundtrip_expected.json";
  run->mesh = makeSyntheticMesh();

  OutputSelection selection;
  selection.stress = true;
  ResultsWriter writer;
  const RunInfo info = syntheticRunInfo();
  writer.open(run->h5Path, info, run->mesh.mesh, selection);
  for (int step = 1; step <= kRoundTripSteps; ++step) {
    SyntheticStep data;
    roundTripStep(step, data);
    for (int attempt = 0; attempt <= data.record.cutbacks; ++attempt) {
      const bool failed = attempt < data.record.cutbacks;
      const int iterations = failed ? 2 : data.record.iterations;
      for (int iteration = 1; iteration <= iterations; ++iteration) {
        run->iterations.push_back(syntheticIteration(step, attempt, iteration));
        writer.appendIteration(run->iterations.back());
      }
      if (failed) {
        run->cutbacks.push_back({step, data.record.time, 0.05,
                                 "residual grew (attempt " + std::to_string(attempt) + ")"});
        writer.appendCutback(run->cutbacks.back());
      }
    }
    writer.writeStep(data.record);
  }
  run->totals = {"completed",
                 kRoundTripSteps,
                 static_cast<int>(run->iterations.size()),
                 static_cast<int>(run->cutbacks.size()),
                 1.25,
                 "all steps converged"};
  writer.close(run->totals);
  std::ofstream(run->jsonPath) << expectedJson(*run, info);
  return run;
}

}  // namespace

const RoundTripRun& roundTripRun() {
  // Removes the run at exit unless it was written for the scripts ($COVCONTACT_OUTPUT_TEST_DIR).
  struct Holder {
    std::unique_ptr<RoundTripRun> run = writeRoundTrip();
    ~Holder() {
      std::error_code ignored;
      if (std::getenv("COVCONTACT_OUTPUT_TEST_DIR") == nullptr)
        fs::remove_all(run->directory, ignored);
    }
  };
  static const Holder holder;
  return *holder.run;
}

void roundTripStep(int step, SyntheticStep& out) {
  static const SyntheticMesh mesh = makeSyntheticMesh();
  fillSyntheticStep(mesh.mesh, step, out);
}

RawArray readRaw(hid_t file, const std::string& path) {
  const hid_t dataset = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (dataset < 0) throw std::runtime_error("no dataset " + path);
  const hid_t space = H5Dget_space(dataset);
  RawArray array;
  array.dims.resize(static_cast<size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, array.dims.data(), nullptr);
  array.values.resize(static_cast<size_t>(H5Sget_simple_extent_npoints(space)));
  if (!array.values.empty())
    H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, array.values.data());
  H5Sclose(space);
  H5Dclose(dataset);
  return array;
}

std::vector<int> readRawInts(hid_t file, const std::string& path) {
  const RawArray array = readRaw(file, path);
  return {array.values.begin(), array.values.end()};
}

double readRawNumberAttribute(hid_t file, const std::string& object, const std::string& name) {
  const hid_t attribute =
      H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  if (attribute < 0) throw std::runtime_error("no attribute " + object + "@" + name);
  double value = 0;
  H5Aread(attribute, H5T_NATIVE_DOUBLE, &value);
  H5Aclose(attribute);
  return value;
}

std::vector<std::string> readRawStringAttribute(hid_t file, const std::string& object,
                                                const std::string& name) {
  const hid_t attribute =
      H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  if (attribute < 0) throw std::runtime_error("no attribute " + object + "@" + name);
  const hid_t space = H5Aget_space(attribute);
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  std::vector<char*> texts(static_cast<size_t>(H5Sget_simple_extent_npoints(space)));
  if (!texts.empty()) H5Aread(attribute, type, texts.data());
  std::vector<std::string> values(texts.begin(), texts.end());
  if (!texts.empty()) H5Dvlen_reclaim(type, space, H5P_DEFAULT, texts.data());
  H5Tclose(type);
  H5Sclose(space);
  H5Aclose(attribute);
  return values;
}

}  // namespace cc::test
