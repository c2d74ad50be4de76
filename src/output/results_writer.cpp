// ResultsWriter: HDF5 file creation, per-step groups with flush, growing convergence/cut-back
// tables, the /summary group, and driving the XDMF and CSV sidecars.
#include "output/results_writer.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "common/utf8.hpp"
#include "output/reactions_csv.hpp"
#include "output/restart_io.hpp"
#include "output/results_layout.hpp"
#include "output/results_mesh.hpp"
#include "output/xdmf_writer.hpp"

namespace cc {

namespace {

namespace fs = std::filesystem;

// Rows per chunk of the growing tables: one chunk (about 40 KiB) holds the Newton history of
// dozens of steps, so appending rarely allocates.
constexpr hsize_t kTableChunkRows = 512;

// The HDF5 1.8 file format. Not 1.10: its superblock marks the file "open for writing", and
// after a SIGKILL every reader refuses the file until `h5clear -s` is run. Not the earliest
// format: its groups (no checksums) were damaged about 4x as often by a kill inside a flush.
// Measured with check_kill.py; numbers in docs/output-format.md.
constexpr H5F_libver_t kFormatLowBound = H5F_LIBVER_V18;
constexpr H5F_libver_t kFormatHighBound = H5F_LIBVER_V18;

// The writer flushes after every Newton iteration and step, so that a run that stops keeps its
// history on disk. HDF5 1.10's flush walks every entry of the metadata cache, which by default
// grows to 32 MiB and keeps the headers of every step group written: at 600 steps of example
// 6.1 the flushes took 16 % of the run (4.7 of 28.8 CPU s, growing with the step count). A
// step's own metadata is a few kilobytes whatever the mesh size (its datasets are contiguous),
// so a fixed cache of 256 KiB holds what the next step touches and the flush stays cheap: 1.1 s
// at 600 steps. (HDF5's evict-on-close would do it too, but the MPI build refuses it.)
constexpr std::size_t kMetadataCacheBytes = 256 * 1024;

void limitMetadataCache(hid_t access, const std::string& path) {
  H5AC_cache_config_t cache;
  cache.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  h5::checkStatus(H5Pget_mdc_config(access, &cache), path, "configuring the metadata cache");
  cache.set_initial_size = true;
  cache.initial_size = kMetadataCacheBytes;
  cache.max_size = kMetadataCacheBytes;
  cache.min_size = std::min(cache.min_size, kMetadataCacheBytes);
  cache.incr_mode = H5C_incr__off;
  cache.flash_incr_mode = H5C_flash_incr__off;
  cache.decr_mode = H5C_decr__off;
  h5::checkStatus(H5Pset_mdc_config(access, &cache), path, "configuring the metadata cache");
}

// replacedByRename: the file is rewritten as a temporary renamed over it (the XDMF), which needs
// a writable directory even when the file itself exists and is writable.
void probeWritable(const fs::path& path, const char* what, bool replacedByRename) {
  const auto fail = [&](const std::string& why) {
    throw OutputError("cannot write " + std::string(what) + " '" + path.string() + "': " + why);
  };
  std::error_code error;
  if (fs::exists(path, error)) {
    if (fs::is_directory(path, error)) fail("it is a directory");
    if (::access(path.c_str(), W_OK) != 0) fail(std::strerror(errno));
    if (!replacedByRename) return;
  }
  const fs::path directory = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(directory, error))
    fail("directory '" + directory.string() + "' does not exist");
  if (::access(directory.c_str(), W_OK | X_OK) != 0)
    fail("directory '" + directory.string() + "': " + std::strerror(errno));
}

h5::Dataset createTable(h5::FileRef file, const char* name, hid_t rowType) {
  const std::string operation = std::string("creating table '") + name + "'";
  const hsize_t initialRows = 0;
  const hsize_t unlimited = H5S_UNLIMITED;
  h5::Space space(h5::check(H5Screate_simple(1, &initialRows, &unlimited), file.path, operation));
  h5::PropertyList creation(h5::check(H5Pcreate(H5P_DATASET_CREATE), file.path, operation));
  h5::checkStatus(H5Pset_chunk(creation.get(), 1, &kTableChunkRows), file.path, operation);
  return h5::Dataset(h5::check(
      H5Dcreate2(file.id, name, rowType, space.get(), H5P_DEFAULT, creation.get(), H5P_DEFAULT),
      file.path, operation));
}

// Every process extends the table (collective with several processes); part 0 writes the row.
void appendRow(h5::FileRef file, hid_t table, const char* name, hid_t rowType, const void* row) {
  const std::string operation = std::string("appending to table '") + name + "'";
  h5::Space current(h5::check(H5Dget_space(table), file.path, operation));
  hsize_t rows = 0;
  H5Sget_simple_extent_dims(current.get(), &rows, nullptr);
  const hsize_t grown = rows + 1;
  const hsize_t one = 1;
  h5::checkStatus(H5Dset_extent(table, &grown), file.path, operation);
  h5::Space fileSpace(h5::check(H5Dget_space(table), file.path, operation));
  h5::checkStatus(
      H5Sselect_hyperslab(fileSpace.get(), H5S_SELECT_SET, &rows, nullptr, &one, nullptr),
      file.path, operation);
  h5::Space memorySpace(h5::check(H5Screate_simple(1, &one, nullptr), file.path, operation));
  hid_t transfer = H5P_DEFAULT;
  if (file.share != nullptr && file.share->parts > 1) {
    transfer = file.share->transfer;
    if (file.share->part != 0) {
      h5::checkStatus(H5Sselect_none(fileSpace.get()), file.path, operation);
      h5::checkStatus(H5Sselect_none(memorySpace.get()), file.path, operation);
    }
  }
  h5::checkStatus(H5Dwrite(table, rowType, memorySpace.get(), fileSpace.get(), transfer, row),
                  file.path, operation);
}

void requireColumns(const StepRecord& step, const char* field, Eigen::Index actual,
                    Eigen::Index expected) {
  if (actual != expected)
    throw std::invalid_argument("step " + std::to_string(step.step) + ": " + field + " has " +
                                std::to_string(actual) + " entries, expected " +
                                std::to_string(expected));
}

void validateContact(const StepRecord& step, const ContactPairRecord& pair) {
  const Eigen::Index points = pair.position.cols();
  const std::string prefix = "contact pair '" + pair.name + "' ";
  const auto require = [&](const char* field, Eigen::Index size) {
    requireColumns(step, (prefix + field).c_str(), size, points);
  };
  require("gap", pair.gap.size());
  require("normal traction", pair.normalTraction.size());
  require("tangential traction", pair.tangentialTraction.cols());
  require("state", pair.state.size());
  require("slip increment", pair.slipIncrement.size());
  require("accumulated slip", pair.accumulatedSlip.size());
  require("weight", pair.weight.size());
  if (pair.stepDissipation.size() > 0) require("step dissipation", pair.stepDissipation.size());
  requireColumns(step, (prefix + "slave nodal force").c_str(), pair.slaveNodalForce.cols(),
                 static_cast<Eigen::Index>(pair.slaveNodes.size()));
}

}  // namespace

std::string xdmfPathFor(const std::string& h5Path) {
  return fs::path(h5Path).replace_extension(".xdmf").string();
}

std::string csvPathFor(const std::string& h5Path) {
  fs::path path(h5Path);
  return (path.parent_path() / (path.stem().string() + "_reactions.csv")).string();
}

void checkOutputWritable(const std::string& h5Path, const OutputSelection& selection,
                         const std::vector<std::string>& inputs) {
  probeWritable(h5Path, "results file", false);
  checkReplaceable(h5Path, OutputKind::Results, inputs);
  if (selection.xdmf) {
    const std::string xdmf = xdmfPathFor(h5Path);
    // `-o run.xdmf`: the sidecar would replace the results it describes.
    if (sameFile(xdmf, h5Path))
      throw OutputError("cannot write results file '" + h5Path +
                        "': its XDMF sidecar would be the same file; name the results file "
                        "*.h5");
    // The XDMF file names the results file in XML, which must be UTF-8.
    if (firstInvalidUtf8(fs::path(h5Path).filename().string()))
      throw OutputError("cannot write results file '" + escapedBytes(h5Path) +
                        "' with an XDMF sidecar: its name is not UTF-8 text; rename it");
    probeWritable(xdmf, "XDMF file", true);
    checkReplaceable(xdmf, OutputKind::Xdmf, inputs);
  }
  if (selection.csv) {
    probeWritable(csvPathFor(h5Path), "CSV file", false);
    checkReplaceable(csvPathFor(h5Path), OutputKind::Csv, inputs);
  }
}

struct ResultsWriter::State {
  ResultsFileLock lock;  // declared first: released after the file is closed
  std::string path;
  h5::WriteShare share;
  h5::PropertyList transfer;  // collective transfers (several processes)
  OutputSelection selection;
  long numNodes = 0;
  long numElements = 0;
  h5::File file;
  h5::Group steps;
  h5::Type convergenceType = layout::convergenceRowType();
  h5::Type cutbackType = layout::cutbackRowType();
  h5::Dataset convergence;
  h5::Dataset cutbacks;
  std::optional<XdmfWriter> xdmf;
  std::optional<ReactionsCsv> csv;

  h5::FileRef ref() const { return {file.get(), path, &share}; }
  void flush() const { h5::checkStatus(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), path, "flushing"); }
  // Closes every HDF5 object and the file (its last metadata is written here).
  void closeFile() {
    convergence.reset();
    cutbacks.reset();
    steps.reset();
    h5::checkStatus(file.close(), path, "closing the file");
  }
};

ResultsWriter::ResultsWriter() = default;

ResultsWriter::~ResultsWriter() {
  h5::QuietErrors quiet;
  if (!state_) return;
  try {
    // An interrupted run closes its file here; closing writes metadata, so readers wait for it.
    const ConsistencyLock change = state_->lock.beginChange();
    state_->closeFile();
  } catch (...) {
    // A destructor must not throw (it may run while an exception unwinds, out of memory too).
    // What interrupted the run is reported by its caller; the steps flushed before stay
    // readable.
  }
  state_.reset();
}

bool ResultsWriter::isOpen() const {
  return state_ != nullptr;
}

const std::string& ResultsWriter::path() const {
  static const std::string none;
  return state_ ? state_->path : none;
}

void ResultsWriter::open(const std::string& path, const RunInfo& info, const Mesh& mesh,
                         const OutputSelection& selection, const ParallelOutput& parallel) {
  if (state_) throw std::logic_error("ResultsWriter::open: '" + state_->path + "' is still open");
  // Checked before the lock (which creates a missing file) and again once it is held: a second
  // run on the same file stops at the lock, before anything is truncated, and the file to be
  // replaced is checked while no other writer can change it. Rank 0 checks and locks for all.
  ResultsFileLock lock;
  std::string refused;
  if (parallel.rank == 0) {
    try {
      checkOutputWritable(path, selection, info.inputFiles);
      lock = ResultsFileLock(path);
      checkOutputWritable(path, selection, info.inputFiles);
    } catch (const OutputError& error) {
      if (parallel.size == 1) throw;
      refused = error.what();
    }
  }
  if (parallel.size > 1) {
    const auto [code, message] = parallel.agree(refused.empty() ? 0 : 1, refused);
    if (code != 0) throw OutputError(message);
  }
  h5::QuietErrors quiet;
  auto state = std::make_unique<State>();
  state->lock = std::move(lock);
  // Readers of the old file wait until the new one has its first flush. Declared after `state`:
  // released before a failure here closes the lock's descriptor.
  const ConsistencyLock change = state->lock.beginChange();
  state->path = path;
  state->selection = selection;
  state->numNodes = mesh.numNodes();
  h5::PropertyList access(h5::check(H5Pcreate(H5P_FILE_ACCESS), path, "creating the file"));
  if (parallel.size > 1) {
    state->transfer =
        h5::PropertyList(h5::check(H5Pcreate(H5P_DATASET_XFER), path, "creating the file"));
    parallel.collective(access.get(), state->transfer.get());
    state->share = {parallel.rank, parallel.size, state->transfer.get()};
  }
  h5::checkStatus(H5Pset_libver_bounds(access.get(), kFormatLowBound, kFormatHighBound), path,
                  "choosing the file format");
  limitMetadataCache(access.get(), path);
  // Our flock (above) excludes other writers; HDF5's own flock would conflict with it.
  h5::checkStatus(H5Pset_file_locking(access.get(), false, true), path, "opening the file");
  state->file =
      h5::File(h5::check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()), path,
                         "creating the file"));
  const h5::FileRef file = state->ref();
  h5::writeAttribute(file, file.id, "format", std::string(layout::kFormatName));
  h5::writeAttribute(file, file.id, "format_version", layout::kFormatVersion);
  h5::writeAttribute(file, file.id, "title", info.title);
  h5::writeAttribute(file, file.id, "version", info.version);
  h5::writeAttribute(file, file.id, "deck_path", info.deckPath);
  h5::writeAttribute(file, file.id, "command_line", info.commandLine);
  h5::writeAttribute(file, file.id, "deck_text", info.deckText);
  h5::writeAttribute(file, file.id, "writing_processes", parallel.size);

  std::vector<XdmfBlock> visualBlocks = writeMesh(file, mesh);
  for (const ElementBlock& block : mesh.blocks) state->numElements += block.connectivity.rows();
  state->steps = h5::createGroup(file, file.id, "steps");
  state->convergence = createTable(file, layout::kConvergence, state->convergenceType.get());
  state->cutbacks = createTable(file, layout::kCutbacks, state->cutbackType.get());
  state->flush();

  // The sidecars are small text files: rank 0 writes them.
  if (selection.xdmf && parallel.rank == 0)
    state->xdmf.emplace(xdmfPathFor(path), fs::path(path).filename().string(), state->numNodes,
                        state->numElements, std::move(visualBlocks));
  if (selection.csv && parallel.rank == 0) state->csv.emplace(csvPathFor(path), selection.contact);
  state_ = std::move(state);
}

void ResultsWriter::writeStep(const StepRecord& step) {
  if (!state_) throw std::logic_error("ResultsWriter::writeStep: no file is open");
  const OutputSelection& selection = state_->selection;
  const auto requireNodal = [&](bool selected, const Eigen::Matrix3Xd* field, const char* name) {
    if (!selected) return;
    if (field == nullptr)
      throw std::invalid_argument("step " + std::to_string(step.step) + ": " + name +
                                  " is selected for output but was not given");
    requireColumns(step, name, field->cols(), state_->numNodes);
  };
  requireNodal(selection.displacement, step.displacement, "displacement");
  requireNodal(selection.reaction, step.reaction, "reaction");
  if (selection.stress && step.stress != nullptr)
    requireColumns(step, "stress", step.stress->cols(), state_->numElements);
  if (selection.contact)
    for (const ContactPairRecord& pair : step.contact) validateContact(step, pair);

  h5::QuietErrors quiet;
  {
    // A reader of the file in progress sees the file before this step or after its flush.
    const ConsistencyLock change = state_->lock.beginChange();
    h5::Group group =
        h5::createGroup(state_->ref(), state_->steps.get(), layout::stepGroupName(step.step));
    writeStepGroup(step, group.get());
    group.reset();
    // Flush before the sidecars mention the step, so they never point at unwritten data.
    state_->flush();
  }

  if (state_->xdmf) {
    XdmfStep shown{step.step,
                   step.time,
                   selection.displacement,
                   selection.reaction,
                   selection.stress && step.stress != nullptr,
                   {}};
    if (selection.contact)
      for (const ContactPairRecord& pair : step.contact)
        shown.contactPairs.emplace_back(pair.name, static_cast<long>(pair.position.cols()));
    state_->xdmf->appendStep(shown);
  }
  if (state_->csv) state_->csv->appendStep(step);
}

void ResultsWriter::writeStepGroup(const StepRecord& step, hid_t group) {
  const h5::FileRef file = state_->ref();
  const OutputSelection& selection = state_->selection;
  h5::writeAttribute(file, group, "step", step.step);
  h5::writeAttribute(file, group, "time", step.time);
  h5::writeAttribute(file, group, "iterations", step.iterations);
  h5::writeAttribute(file, group, "cutbacks", step.cutbacks);
  const auto numNodes = static_cast<hsize_t>(state_->numNodes);
  if (selection.displacement)
    h5::writeDoubles(file, group, layout::kDisplacement, step.displacement->data(), numNodes, 3);
  if (selection.reaction)
    h5::writeDoubles(file, group, layout::kReaction, step.reaction->data(), numNodes, 3);
  if (selection.stress && step.stress != nullptr)
    h5::writeDoubles(file, group, layout::kStress, step.stress->data(),
                     static_cast<hsize_t>(step.stress->cols()), layout::kStressComponents);

  Eigen::Matrix3Xd setForces(3, static_cast<Eigen::Index>(step.setReactions.size()));
  std::vector<std::string> setNames;
  for (const auto& [name, force] : step.setReactions) {
    setForces.col(static_cast<Eigen::Index>(setNames.size())) = force;
    setNames.push_back(name);
  }
  h5::Dataset setReactions =
      h5::writeDoubles(file, group, layout::kSetReactions, setForces.data(), setNames.size(), 3);
  h5::writeAttribute(file, setReactions.get(), "names", setNames);
  if (selection.contact && !step.contact.empty()) writeContact(step, group);
  writeEnergy(file, group, step.energy);
  if (step.restart != nullptr) writeRestart(file, group, *step.restart, !selection.displacement);
}

// The energy balance of the step (EnergyRecord) as attributes of /steps/<n>/energy.
void ResultsWriter::writeEnergy(h5::FileRef file, hid_t stepGroup, const EnergyRecord& energy) {
  h5::Group group = h5::createGroup(file, stepGroup, layout::kEnergyGroup);
  const hid_t id = group.get();
  h5::writeAttribute(file, id, "external_work", energy.externalWork);
  h5::writeAttribute(file, id, "strain_energy", energy.strainEnergy);
  h5::writeAttribute(file, id, "contact_energy", energy.contactEnergy);
  h5::writeAttribute(file, id, "dissipation", energy.dissipation);
  h5::writeAttribute(file, id, "dissipation_power", energy.dissipationPower);
  h5::writeAttribute(file, id, "stabilization_dissipation", energy.stabilizationDissipation);
  h5::writeAttribute(file, id, "balance", energy.balance);
  h5::writeAttribute(file, id, "quadrature_bound", energy.quadratureBound);
}

void ResultsWriter::writeContact(const StepRecord& step, hid_t stepGroup) {
  const h5::FileRef file = state_->ref();
  h5::Group contact = h5::createGroup(file, stepGroup, layout::kContactGroup);
  for (const ContactPairRecord& pair : step.contact) {
    h5::Group group = h5::createGroup(file, contact.get(), layout::linkName(pair.name));
    const hid_t id = group.get();
    const auto points = static_cast<hsize_t>(pair.position.cols());
    h5::writeAttribute(file, id, "name", pair.name);
    h5::writeDoubles(file, id, "position", pair.position.data(), points, 3);
    h5::writeDoubles(file, id, "gap", pair.gap.data(), points, 0);
    h5::writeDoubles(file, id, "normal_traction", pair.normalTraction.data(), points, 0);
    h5::writeDoubles(file, id, "tangential_traction", pair.tangentialTraction.data(), points, 3);
    h5::writeInts(file, id, "state", pair.state.data(), points, 0);
    h5::writeDoubles(file, id, "slip_increment", pair.slipIncrement.data(), points, 0);
    h5::writeDoubles(file, id, "accumulated_slip", pair.accumulatedSlip.data(), points, 0);
    h5::writeDoubles(file, id, "weight", pair.weight.data(), points, 0);
    // Empty in a hand-built record: every point on the master.
    const Eigen::VectorXd edgeShare =
        pair.edgeShare.size() > 0 ? pair.edgeShare
                                  : Eigen::VectorXd::Ones(static_cast<Eigen::Index>(points));
    h5::writeDoubles(file, id, "edge_share", edgeShare.data(), points, 0);
    const Eigen::VectorXi vertexIds = Eigen::VectorXi::LinSpaced(static_cast<Eigen::Index>(points),
                                                                 0, static_cast<int>(points) - 1);
    h5::writeInts(file, id, layout::kVertexIds, vertexIds.data(), points, 0);
    h5::writeDoubles(file, id, layout::kTotalForce, pair.totalForce.data(), 3, 0);
    h5::writeInts(file, id, "slave_nodes", pair.slaveNodes.data(), pair.slaveNodes.size(), 0);
    h5::writeDoubles(file, id, "slave_nodal_force", pair.slaveNodalForce.data(),
                     pair.slaveNodes.size(), 3);
    // Optional in the record (a writer test builds records by hand); every contact pair fills it.
    if (pair.stepDissipation.size() > 0) {
      h5::writeDoubles(file, id, "step_dissipation", pair.stepDissipation.data(), points, 0);
    }
    h5::writeAttribute(file, id, "eps_n", pair.penaltyNormal);
    h5::writeAttribute(file, id, "eps_t", pair.penaltyTangential);
    h5::writeAttribute(file, id, "eps_automatic", pair.automaticPenalty ? 1 : 0);
    h5::writeAttribute(file, id, "penalty_energy", pair.penaltyEnergy);
    h5::writeAttribute(file, id, "dissipation", pair.dissipation);
    h5::writeAttribute(file, id, "dissipated_energy", pair.dissipatedEnergy);
    h5::writeAttribute(file, id, "dissipation_power", pair.dissipationPower);
  }
}

void ResultsWriter::appendIteration(const IterationRecord& iteration) {
  if (!state_) throw std::logic_error("ResultsWriter::appendIteration: no file is open");
  h5::QuietErrors quiet;
  const layout::ConvergenceRow row{
      iteration.step,   iteration.attempt,        iteration.iteration,
      iteration.time,   iteration.residualNorm,   iteration.relativeResidual,
      iteration.energy, iteration.relativeEnergy, iteration.wallSeconds};
  // Flushed at once, like a step: the history of a step that fails is what a user looks at.
  const ConsistencyLock change = state_->lock.beginChange();
  appendRow(state_->ref(), state_->convergence.get(), layout::kConvergence,
            state_->convergenceType.get(), &row);
  state_->flush();
}

void ResultsWriter::appendCutback(const CutbackRecord& cutback) {
  if (!state_) throw std::logic_error("ResultsWriter::appendCutback: no file is open");
  h5::QuietErrors quiet;
  const layout::CutbackRow row =
      layout::cutbackRow(cutback.step, cutback.time, cutback.newDt, cutback.reason);
  const ConsistencyLock change = state_->lock.beginChange();
  appendRow(state_->ref(), state_->cutbacks.get(), layout::kCutbacks, state_->cutbackType.get(),
            &row);
  state_->flush();
}

void ResultsWriter::close(const RunTotals& totals) {
  if (!state_) throw std::logic_error("ResultsWriter::close: no file is open");
  h5::QuietErrors quiet;
  std::unique_ptr<State> state = std::move(state_);
  const ConsistencyLock change = state->lock.beginChange();
  const h5::FileRef file = state->ref();
  {
    h5::Group summary = h5::createGroup(file, file.id, "summary");
    h5::writeAttribute(file, summary.get(), "outcome", totals.outcome);
    h5::writeAttribute(file, summary.get(), "steps", totals.steps);
    h5::writeAttribute(file, summary.get(), "total_iterations", totals.totalIterations);
    h5::writeAttribute(file, summary.get(), "cutbacks", totals.cutbacks);
    h5::writeAttribute(file, summary.get(), "line_search_retries", totals.lineSearchRetries);
    h5::writeAttribute(file, summary.get(), "discarded_iterations", totals.discardedIterations);
    h5::writeAttribute(file, summary.get(), "continuation_retries", totals.continuationRetries);
    h5::writeAttribute(file, summary.get(), "stabilized_retries", totals.stabilizedRetries);
    h5::writeAttribute(file, summary.get(), "wall_seconds", totals.wallSeconds);
    h5::writeAttribute(file, summary.get(), "message", totals.message);
    h5::writeAttribute(file, summary.get(), "warnings", totals.warnings);
    h5::writeAttribute(file, summary.get(), "linear_solver", totals.linearSolver);
    h5::writeAttribute(file, summary.get(), "krylov_iterations",
                       static_cast<int>(totals.krylovIterations));
    h5::writeAttribute(file, summary.get(), "krylov_fallbacks", totals.krylovFallbacks);
  }
  state->closeFile();
}

}  // namespace cc
