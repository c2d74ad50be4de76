// Model: the NonlinearProblem the solver works on, and the step records for output.
#include "model/model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

namespace cc {

Model::~Model() = default;

OutputSelection outputSelection(const OutputSpec& output) {
  OutputSelection selection;
  selection.displacement = output.displacement;
  selection.reaction = output.reaction;
  selection.stress = output.stress;
  selection.contact = output.contact;
  selection.csv = output.csv;
  selection.xdmf = output.xdmf;
  return selection;
}

void Model::prescribedValues(double t, Eigen::VectorXd& values) const {
  boundaryConditions_.prescribedValues(t, dofs_, mesh_.coordinates, values);
}

void Model::externalForces(double t, Eigen::VectorXd& force) const {
  boundaryConditions_.externalForces(t, mesh_.coordinates, force);
}

void Model::rigidSurfaceOffsets(double t, Eigen::VectorXd& offsets) const {
  std::vector<Eigen::Vector3d> moving;
  for (const auto& pair : contactPairs_) {
    if (auto offset = pair->surfaceOffsetAt(t)) moving.push_back(*offset);
  }
  offsets.resize(3 * static_cast<Eigen::Index>(moving.size()));
  for (std::size_t i = 0; i < moving.size(); ++i) {
    offsets.segment<3>(3 * static_cast<Eigen::Index>(i)) = moving[i];
  }
}

void Model::assemble(const AssemblyState& state, Eigen::VectorXd& internalForce,
                     SystemMatrices* tangent) {
  viscousFactor_ = state.viscousFactor;
  if (!group_) {
    assembler_->assemble(state, internalForce, tangent);
    return;
  }
  // Several processes: an element failing on one process fails the iteration on all of them,
  // with that process's message.
  int failure = 0;
  std::string message;
  try {
    assembler_->assemble(state, internalForce, tangent);
  } catch (const StepFailure& error) {
    failure = 1 + static_cast<int>(error.kind());
    message = error.what();
  }
  const auto [code, text] = group_->agree(failure, message);
  if (code != 0) throw StepFailure(static_cast<FailureKind>(code - 1), text);
  rememberAssemblyState(state);
  group_->sum(internalForce.data(), static_cast<std::size_t>(internalForce.size()));
  if (tangent) {
    // Each process saw the symmetry of its own items only.
    tangent->symmetric = group_->maximum(tangent->symmetric ? 0 : 1) == 0;
    // Each process's pattern holds only its own items: when any of them changed, all take a
    // new version, so that the distributed matrix is rebuilt by all of them together.
    const bool changed = tangent->patternVersion != sharedPatternVersion_;
    if (group_->maximum(changed ? 1 : 0) != 0 && !changed) {
      tangent->patternVersion = newPatternVersion();
    }
    sharedPatternVersion_ = tangent->patternVersion;
  }
}

void Model::sumOverProcesses(Eigen::VectorXd& values) {
  if (group_) group_->sum(values.data(), static_cast<std::size_t>(values.size()));
}

NonlinearProblem::Augmentation Model::augment() {
  completeContactTrials();
  Augmentation result;
  for (auto& pair : contactPairs_) {
    const contact::ContactPair::Augmentation status = pair->augment();
    if (std::string note = pair->takeAugmentationNote(); !note.empty()) {
      result.note += (result.note.empty() ? "" : "\n") + note;
    }
    switch (status) {
      case contact::ContactPair::Augmentation::Converged:
        break;
      case contact::ContactPair::Augmentation::Updated:
        result.status = Augmentation::Status::Updated;
        break;
      case contact::ContactPair::Augmentation::Failed:
        return {Augmentation::Status::Failed, pair->augmentationMessage(), result.note};
    }
  }
  return result;
}

double Model::stiffestPenaltyRatio() const {
  double ratio = 0;
  for (const auto& pair : contactPairs_) ratio = std::max(ratio, pair->penaltyRatio());
  return ratio;
}

void Model::scalePenalties(double factor) {
  for (auto& pair : contactPairs_) pair->scalePenalties(factor);
}

void Model::commitStep() {
  completeContactTrials();
  for (auto& set : elementSets_) set->commitStep();
  for (auto& pair : contactPairs_) pair->commitStep();
  if (group_) {
    shareElementHistory();
    countMasterOwnerChanges();
  }
}

PendingCrossings Model::pendingContactCrossings() {
  PendingCrossings pending;
  for (const auto& pair : contactPairs_) pending += pair->pendingCrossings();
  if (!group_) return pending;
  double counts[2] = {double(pending.first), double(pending.repeated)};
  group_->sum(counts, 2);
  return {static_cast<int>(counts[0]), static_cast<int>(counts[1])};
}

ContactChanges Model::takeContactChanges() {
  ContactChanges changes;
  for (auto& pair : contactPairs_) changes += pair->takeChanges();
  if (!group_) return changes;
  // Each process counted and fingerprinted the points it evaluated. The counts are summed; the
  // fingerprints too, modulo 2^64, in 16-bit pieces that double sums carry exactly: the same on
  // every process (Newton's cycle test must decide alike everywhere), and it comes back exactly
  // when every process's own active set does.
  constexpr int kPieces = 4;
  double values[3 + kPieces] = {double(changes.state), double(changes.segment),
                                double(changes.active)};
  for (int k = 0; k < kPieces; ++k)
    values[3 + k] = double((changes.signature >> (16 * k)) & 0xFFFF);
  group_->sum(values, 3 + kPieces);
  ContactChanges total{static_cast<int>(values[0]), static_cast<int>(values[1]),
                       static_cast<int>(values[2])};
  for (int k = 0; k < kPieces; ++k) {
    total.signature += static_cast<std::uint64_t>(values[3 + k]) << (16 * k);
  }
  return total;
}

void Model::restoreStep() {
  for (auto& set : elementSets_) set->restoreStep();
  for (auto& pair : contactPairs_) pair->restoreStep();
}

// The points that changed most often since the step's last commit or restore, at least
// kSwitchingAtLeast times each: a stalled solve's few switching points (issue 14: two points
// switching stick/slip at every step length of the line search), not the many that change once
// as the contact zone moves. Counts are summed over the processes, which evaluate disjoint
// points.
std::string Model::describeSwitchingContact() {
  constexpr int kSwitchingAtLeast = 3;
  constexpr std::size_t kNamed = 3;
  struct Switching {
    int changes, state, segment;
    std::string where;
  };
  std::vector<Switching> found;
  for (const auto& pair : contactPairs_) {
    const std::vector<int>& state = pair->stateChangesInAttempt();
    const std::vector<int>& segment = pair->segmentChangesInAttempt();
    std::vector<double> counts(2 * static_cast<std::size_t>(pair->pointCount()), 0.0);
    for (std::size_t i = 0; i < state.size() && i < segment.size(); ++i) {
      counts[2 * i] = state[i];
      counts[2 * i + 1] = segment[i];
    }
    if (group_) group_->sum(counts.data(), counts.size());
    for (std::size_t i = 0; 2 * i < counts.size(); ++i) {
      const int stateChanges = static_cast<int>(counts[2 * i]);
      const int segmentChanges = static_cast<int>(counts[2 * i + 1]);
      if (stateChanges + segmentChanges < kSwitchingAtLeast) continue;
      const int node = pair->nearestNode(i);
      found.push_back({stateChanges + segmentChanges, stateChanges, segmentChanges,
                       fmt::format("{} point {}{}", pair->name(), i,
                                   node >= 0 ? " at " + nodeLabel(node) : std::string())});
    }
  }
  if (found.empty()) return {};
  std::stable_sort(found.begin(), found.end(),
                   [](const Switching& a, const Switching& b) { return a.changes > b.changes; });
  std::string text = fmt::format("{} contact point{} kept changing in this attempt: ", found.size(),
                                 found.size() == 1 ? "" : "s");
  for (std::size_t k = 0; k < found.size() && k < kNamed; ++k) {
    text += fmt::format("{}{} ({} state and {} segment changes)", k > 0 ? ", " : "", found[k].where,
                        found[k].state, found[k].segment);
  }
  if (found.size() > kNamed) text += ", ...";
  return text;
}

std::string Model::nodeLabel(int node) const {
  return mesh_.nodeName(node);
}

void Model::rememberContactSearch() {
  for (auto& pair : contactPairs_) pair->rememberSearch();
}

void Model::recallContactSearch() {
  for (auto& pair : contactPairs_) pair->recallSearch();
}

int Model::elementCount() const {
  int count = 0;
  for (const auto& set : elementSets_) count += set->elementCount();
  return count;
}

int Model::contactPointCount() const {
  int count = 0;
  for (const auto& pair : contactPairs_) count += pair->pointCount();
  return count;
}

StepRecord Model::stepRecord(int step, double time, int iterations, int cutbacks,
                             const Eigen::VectorXd& displacement,
                             const Eigen::VectorXd& internalForce, bool withStress) {
  const int n = mesh_.numNodes();
  StepRecord record;
  record.step = step;
  record.time = time;
  record.iterations = iterations;
  record.cutbacks = cutbacks;
  displacementBuffer_ = Eigen::Map<const Eigen::Matrix3Xd>(displacement.data(), 3, n);
  record.displacement = &displacementBuffer_;

  // Reactions: the out-of-balance force f_int - f_ext at the Dirichlet dofs (zero elsewhere).
  Eigen::VectorXd external;
  externalForces(time, external);
  const Eigen::VectorXd unbalanced = internalForce - external;
  reactionBuffer_.setZero(3, n);
  for (int dof : dofs_.prescribedDofs()) reactionBuffer_(dof % 3, dof / 3) = unbalanced[dof];
  record.reaction = &reactionBuffer_;
  for (const std::string& name : reactionSets_) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int node : mesh_.nodeSets.at(name).nodes) sum += unbalanced.segment<3>(3 * node);
    record.setReactions.emplace_back(name, sum);
  }

  if (withStress) {
    const Eigen::Matrix3Xd current = mesh_.coordinates + displacementBuffer_;
    stressBuffer_.resize(6, elementCount());
    int column = 0;
    for (const auto& set : elementSets_) {
      const auto stress = set->cauchyStress(mesh_.coordinates, current);
      stressBuffer_.middleCols(column, stress.cols()) = stress;
      column += static_cast<int>(stress.cols());
    }
    record.stress = &stressBuffer_;
  }
  for (const auto& pair : contactPairs_) {
    record.contact.push_back(pair->record());
    // Mean power over the step accounted last (accountEnergy runs before the record is taken).
    record.contact.back().dissipationPower =
        energyStepLength_ > 0 ? pair->stepDissipation() / energyStepLength_ : 0.0;
  }
  record.energy = energy_;
  return record;
}

}  // namespace cc
