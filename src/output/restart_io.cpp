// Writing and reading the restart group of a step (see restart_io.hpp).
#include "output/restart_io.hpp"

#include <algorithm>

#include "output/results_layout.hpp"
#include "output/results_reader.hpp"

namespace cc {

namespace {

std::string restartGroupPath(int step) {
  return layout::stepGroupPath(step) + "/" + layout::kRestartGroup;
}

// The step's increment (nodes x 3) and attribute last_dt, when a phase extrapolates.
constexpr const char* kLastIncrement = "last_increment";
// The energy account (RestartRecord::Energy): the support reactions at the prescribed dofs
// (dofs x 1) and per contact pair its rigid surface's force and dissipation (pairs x 4), with
// the running sums as attributes of the first.
constexpr const char* kEnergyReactions = "energy_reactions";
constexpr const char* kEnergyPairs = "energy_pairs";
// After a stabilised step: its increment (nodes x 3), its C / dt an attribute of the reactions.
constexpr const char* kEnergyViscousIncrement = "energy_viscous_increment";

// Datasets of one history group keep the user's name in the "name" attribute (link names
// replace '/', see layout::linkName).
void writeNamed(h5::FileRef file, hid_t group, const std::string& name, const double* data,
                hsize_t rows, hsize_t cols) {
  h5::Dataset dataset = h5::writeDoubles(file, group, layout::linkName(name), data, rows, cols);
  h5::writeAttribute(file, dataset.get(), "name", name);
}

void writeEnergy(h5::FileRef file, hid_t group, const RestartRecord::Energy& energy) {
  if (energy.pairs.cols() != 4) return;  // no step booked
  static constexpr double kNoValue = 0;  // HDF5 wants a buffer even for no values
  const h5::Dataset reactions =
      h5::writeDoubles(file, group, kEnergyReactions,
                       energy.reactions.size() > 0 ? energy.reactions.data() : &kNoValue,
                       static_cast<hsize_t>(energy.reactions.size()), 0);
  h5::writeAttribute(file, reactions.get(), "external_work", energy.externalWork);
  h5::writeAttribute(file, reactions.get(), "stabilization_dissipation",
                     energy.stabilizationDissipation);
  h5::writeAttribute(file, reactions.get(), "quadrature_bound", energy.quadratureBound);
  if (energy.viscousRate > 0 && energy.viscousIncrement.size() > 0) {
    h5::writeAttribute(file, reactions.get(), "viscous_rate", energy.viscousRate);
    h5::writeDoubles(file, group, kEnergyViscousIncrement, energy.viscousIncrement.data(),
                     static_cast<hsize_t>(energy.viscousIncrement.size() / 3), 3);
  }
  const Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> pairs = energy.pairs;
  h5::writeDoubles(file, group, kEnergyPairs, pairs.size() > 0 ? pairs.data() : &kNoValue,
                   static_cast<hsize_t>(pairs.rows()), 4);
}

void readEnergy(const ResultsReader& reader, const std::string& group,
                RestartRecord::Energy& energy) {
  const std::string reactions = group + "/" + kEnergyReactions;
  if (!reader.hasDataset(reactions) || !reader.hasDataset(group + "/" + kEnergyPairs)) return;
  const Eigen::MatrixXd values = reader.readMatrix(reactions);
  energy.reactions = Eigen::Map<const Eigen::VectorXd>(values.data(), values.size());
  energy.externalWork = reader.numberAttribute(reactions, "external_work");
  energy.stabilizationDissipation = reader.numberAttribute(reactions, "stabilization_dissipation");
  energy.quadratureBound = reader.numberAttribute(reactions, "quadrature_bound");
  energy.pairs = reader.readMatrix(group + "/" + kEnergyPairs);
  if (reader.hasDataset(group + "/" + kEnergyViscousIncrement)) {
    energy.viscousRate = reader.numberAttribute(reactions, "viscous_rate");
    const Eigen::MatrixXd byNode =
        reader.readMatrix(group + "/" + kEnergyViscousIncrement).transpose();
    energy.viscousIncrement = Eigen::Map<const Eigen::VectorXd>(byNode.data(), byNode.size());
  }
}

}  // namespace

void writeRestart(h5::FileRef file, hid_t stepGroup, const RestartRecord& restart,
                  bool withDisplacement) {
  h5::Group group = h5::createGroup(file, stepGroup, layout::kRestartGroup);
  h5::writeAttribute(file, group.get(), "step_fraction", restart.stepFraction);
  h5::writeAttribute(file, group.get(), "easy_steps", restart.easySteps);
  h5::writeAttribute(file, group.get(), "with_displacement", withDisplacement ? 1 : 0);
  if (withDisplacement) {
    h5::writeDoubles(file, group.get(), layout::kDisplacement, restart.displacement.data(),
                     static_cast<hsize_t>(restart.displacement.size() / 3), 3);
  }
  if (restart.lastIncrement.size() > 0) {
    h5::writeAttribute(file, group.get(), "last_dt", restart.lastDt);
    h5::writeDoubles(file, group.get(), kLastIncrement, restart.lastIncrement.data(),
                     static_cast<hsize_t>(restart.lastIncrement.size() / 3), 3);
  }
  if (restart.viscousFactor > 0) {
    h5::writeAttribute(file, group.get(), "viscous_factor", restart.viscousFactor);
  }
  if (restart.viscousFactorFromStiffness) {
    h5::writeAttribute(file, group.get(), "viscous_factor_from_stiffness", 1);
  }
  if (restart.stabilizing) {
    h5::writeAttribute(file, group.get(), "stabilized_easy_steps", restart.stabilizedEasySteps);
  }
  writeEnergy(file, group.get(), restart.energy);
  h5::Group elements = h5::createGroup(file, group.get(), layout::kElementHistoryGroup);
  for (const auto& [name, values] : restart.elementHistory) {
    // An empty history (Hex8) is written as an empty dataset so that the set is still listed;
    // HDF5 wants a buffer even for no values.
    static constexpr double kNoValue = 0;
    writeNamed(file, elements.get(), name, values.empty() ? &kNoValue : values.data(),
               values.size(), 0);
  }
  h5::Group contact = h5::createGroup(file, group.get(), layout::kContactHistoryGroup);
  for (const auto& [name, table] : restart.contactHistory) {
    // Column-major rows x points is row-major points x rows: one row per point in the file.
    writeNamed(file, contact.get(), name, table.data(), static_cast<hsize_t>(table.cols()),
               static_cast<hsize_t>(table.rows()));
  }
}

std::vector<int> restartSteps(const std::string& path) {
  const ResultsReader reader(path);
  std::vector<int> steps;
  for (const StepHeader& header : reader.steps()) {
    if (reader.hasGroup(restartGroupPath(header.step))) steps.push_back(header.step);
  }
  std::sort(steps.begin(), steps.end());
  return steps;
}

RestartPoint readRestart(const std::string& path, int step) {
  const ResultsReader reader(path);
  const std::vector<int> available = restartSteps(path);
  if (available.empty()) {
    throw OutputError("'" + path + "' holds no restart data (no converged step was written)");
  }
  if (step < 0) step = available.back();
  if (!std::binary_search(available.begin(), available.end(), step)) {
    throw OutputError("'" + path + "' has no restart data for step " + std::to_string(step) +
                      "; steps with restart data: " + std::to_string(available.front()) + " to " +
                      std::to_string(available.back()) + " (" + std::to_string(available.size()) +
                      " steps)");
  }
  RestartPoint point;
  point.step = step;
  const std::string stepPath = layout::stepGroupPath(step);
  const std::string group = restartGroupPath(step);
  point.time = reader.numberAttribute(stepPath, "time");
  RestartRecord& record = point.record;
  record.stepFraction = reader.numberAttribute(group, "step_fraction");
  record.easySteps = static_cast<int>(reader.numberAttribute(group, "easy_steps"));
  const bool own = reader.numberAttribute(group, "with_displacement") != 0;
  const Eigen::MatrixXd nodal =
      reader.readMatrix((own ? group : stepPath) + "/" + layout::kDisplacement);
  const Eigen::MatrixXd byNode = nodal.transpose();  // 3 x numNodes, column-major = node-major
  record.displacement = Eigen::Map<const Eigen::VectorXd>(byNode.data(), byNode.size());
  if (reader.hasDataset(group + "/" + kLastIncrement)) {
    const Eigen::MatrixXd increment = reader.readMatrix(group + "/" + kLastIncrement).transpose();
    record.lastIncrement = Eigen::Map<const Eigen::VectorXd>(increment.data(), increment.size());
    record.lastDt = reader.numberAttribute(group, "last_dt");
  }
  if (reader.hasAttribute(group, "viscous_factor")) {
    record.viscousFactor = reader.numberAttribute(group, "viscous_factor");
  }
  record.viscousFactorFromStiffness = reader.hasAttribute(group, "viscous_factor_from_stiffness");
  // Written only while a run stabilises on failure (files without it: not stabilising).
  if (reader.hasAttribute(group, "stabilized_easy_steps")) {
    record.stabilizing = true;
    record.stabilizedEasySteps =
        static_cast<int>(reader.numberAttribute(group, "stabilized_easy_steps"));
  }
  readEnergy(reader, group, record.energy);
  const std::string elements = group + "/" + layout::kElementHistoryGroup;
  for (const std::string& link : reader.children(elements)) {
    const std::string dataset = elements + "/" + link;
    const Eigen::MatrixXd values = reader.readMatrix(dataset);
    record.elementHistory.emplace_back(
        reader.stringAttribute(dataset, "name"),
        std::vector<double>(values.data(), values.data() + values.size()));
  }
  const std::string contact = group + "/" + layout::kContactHistoryGroup;
  for (const std::string& link : reader.children(contact)) {
    const std::string dataset = contact + "/" + link;
    record.contactHistory.emplace_back(reader.stringAttribute(dataset, "name"),
                                       reader.readMatrix(dataset).transpose());
  }
  return point;
}

}  // namespace cc
