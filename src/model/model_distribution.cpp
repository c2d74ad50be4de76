// Model::distribute and the sharing of element history: who evaluates what in a run on several
// processes (issue 17). Every process holds the whole mesh and the whole state (the mesh is
// replicated, as MOOSE's default mesh is; docs/performance/distributed.md says up to which size
// that holds); only the element work and the rows of the linear system are divided.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <numeric>

#include "common/errors.hpp"
#include "model/model.hpp"

namespace cc {

namespace {

// Nodes sharing an element are neighbours (the graph of the stiffness matrix's node blocks).
void nodeGraph(const std::vector<std::unique_ptr<ElementSet>>& sets, int numNodes,
               std::vector<int>& offsets, std::vector<int>& adjacency) {
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(numNodes));
  for (const auto& set : sets) {
    for (std::size_t e = 0; e < set->itemCount(); ++e) {
      const std::span<const int> nodes = set->itemNodes(e);
      for (int a : nodes) {
        for (int b : nodes) {
          if (a != b) neighbours[static_cast<std::size_t>(a)].push_back(b);
        }
      }
    }
  }
  offsets.assign(1, 0);
  adjacency.clear();
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    adjacency.insert(adjacency.end(), list.begin(), list.end());
    offsets.push_back(static_cast<int>(adjacency.size()));
    std::vector<int>().swap(list);
  }
}

// The process owning most of an element's nodes (the lowest such rank on a tie).
int elementOwner(std::span<const int> nodes, const std::vector<int>& nodeOwner,
                 std::vector<int>& votes) {
  std::fill(votes.begin(), votes.end(), 0);
  for (int node : nodes)
    ++votes[static_cast<std::size_t>(nodeOwner[static_cast<std::size_t>(node)])];
  return static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
}

}  // namespace

std::string Model::distribute(ProcessGroup& group) {
  if (group.size() == 1) return {};
  // integration=segments rebuilds its points from the converged configuration with decisions
  // (which master edge splits a slave segment, which piece is a sliver) that jump where edges
  // align: round-off differences between 1 and N processes (1e-9) changed the number of points
  // and the iteration counts (parallel.segments). Until the segmentation is made insensitive to
  // that, runs on several processes refuse it rather than drift from the serial run.
  for (const ContactSpec& contact : spec_.contacts) {
    if (contact.integration == ContactSpec::Integration::Segments) {
      throw InputError(contact.where,
                       "contact: integration=segments is not available on several processes "
                       "yet (its segmentation is not reproducible across process counts); run "
                       "on one process or use integration=gauss");
    }
  }
  group_ = &group;
  std::vector<int> offsets, adjacency;
  nodeGraph(elementSets_, mesh_.numNodes(), offsets, adjacency);
  nodeOwner_ = group.partition(offsets, adjacency);
  const std::size_t processes = static_cast<std::size_t>(group.size());
  std::vector<int> votes(processes), elementsOf(processes, 0), nodesOf(processes, 0);
  for (int owner : nodeOwner_) ++nodesOf[static_cast<std::size_t>(owner)];
  ownsElement_.clear();
  for (const auto& set : elementSets_) {
    std::vector<char>& owns = ownsElement_.emplace_back(set->itemCount(), 0);
    for (std::size_t e = 0; e < set->itemCount(); ++e) {
      const int owner = elementOwner(set->itemNodes(e), nodeOwner_, votes);
      ++elementsOf[static_cast<std::size_t>(owner)];
      owns[e] = owner == group.rank();
    }
  }
  // Contributions are the element sets, then the contact pairs (model_builder.cpp).
  const std::size_t numSets = elementSets_.size();
  std::vector<char> ownedNodes(nodeOwner_.size(), 0);
  for (std::size_t n = 0; n < nodeOwner_.size(); ++n) ownedNodes[n] = nodeOwner_[n] == group.rank();
  assembler_->setItemFilter(
      [this, numSets](std::size_t contribution, std::size_t item) {
        if (contribution < numSets) {
          return ownsElement_[contribution][item] ? ItemRole::Assemble : ItemRole::Skip;
        }
        return ownsContactPoint(*contactPairs_[contribution - numSets], item) ? ItemRole::Assemble
                                                                              : ItemRole::Skip;
      },
      std::move(ownedNodes));
  std::vector<int> pointsOf(processes, 0);
  for (const auto& pair : contactPairs_) {
    for (std::size_t item = 0; item < pair->itemCount(); ++item) {
      ++pointsOf[static_cast<std::size_t>(contactPointOwner(*pair, item))];
    }
  }
  const auto [fewestNodes, mostNodes] = std::minmax_element(nodesOf.begin(), nodesOf.end());
  const auto [fewestElements, mostElements] =
      std::minmax_element(elementsOf.begin(), elementsOf.end());
  const auto [fewestPoints, mostPoints] = std::minmax_element(pointsOf.begin(), pointsOf.end());
  return fmt::format(
      "{} processes (Scotch partition): {}-{} nodes, {}-{} elements and {}-{} contact points "
      "per process, whole mesh on each",
      group.size(), *fewestNodes, *mostNodes, *fewestElements, *mostElements, *fewestPoints,
      *mostPoints);
}

// The committed history of an element lives on its owner; after a step every process gets it
// (stress output, energy and restart read the whole history; a cut-back restores it).
void Model::shareElementHistory() {
  for (std::size_t s = 0; s < elementSets_.size(); ++s) {
    ElementSet& set = *elementSets_[s];
    std::vector<double> history = set.exportHistory();
    if (history.empty()) continue;
    const std::size_t perElement = history.size() / set.itemCount();
    for (std::size_t e = 0; e < set.itemCount(); ++e) {
      if (!ownsElement_[s][e]) {
        std::fill_n(history.begin() + static_cast<std::ptrdiff_t>(e * perElement), perElement, 0.0);
      }
    }
    group_->sum(history.data(), history.size());
    set.importHistory(history);
  }
}

// Contact points are dealt out in turn (point k to process k mod P), not by the owner of their
// nodes: the partition balances nodes, and a contact surface often lies inside one part (the
// scaling decks put every point on one of 2 processes). Dealt in turn rather than in blocks of
// the index, because the points in contact are usually a contiguous run of indices (the part of
// a slave surface under a smaller master) and would fall into one block. Any process can
// evaluate any point (the state is replicated); entries of rows another process owns travel
// with PETSc's matrix assembly, like those of elements on a partition boundary.
int Model::contactPointOwner(const contact::ContactPair&, std::size_t item) const {
  return static_cast<int>(item % static_cast<std::size_t>(group_->size()));
}

bool Model::ownsContactPoint(const contact::ContactPair& pair, std::size_t item) const {
  return contactPointOwner(pair, item) == group_->rank();
}

void Model::rememberAssemblyState(const AssemblyState& state) {
  lastState_ = state;
  lastCurrent_ = *state.current;
  lastPrevious_ = *state.previous;
  lastState_.current = &lastCurrent_;
  lastState_.previous = &lastPrevious_;
  contactTrialsComplete_ = false;
}

// In Newton's iterations a process evaluates only its own contact points. Once a solve has
// converged, the history to commit, the Uzawa update and the output need every point's trial
// state on every process: the others' points are evaluated here, once per converged solve, at
// the configuration of the last assembly (the converged one: Newton assembles there last).
// The search ran everywhere at that configuration, so this reproduces the owner's evaluation
// bit for bit; it cannot fail where the owner's did not.
void Model::completeContactTrials() {
  if (!group_ || contactTrialsComplete_) return;
  contactTrialsComplete_ = true;
  const auto start = std::chrono::steady_clock::now();
  Eigen::VectorXd force;
  for (auto& pair : contactPairs_) {
    for (std::size_t item = 0; item < pair->itemCount(); ++item) {
      if (ownsContactPoint(*pair, item)) continue;
      force.setZero(3 * static_cast<Eigen::Index>(pair->itemNodes(item).size()));
      (void)pair->evaluate(item, lastState_, force, nullptr);
    }
  }
  contactCompletionSeconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void Model::countMasterOwnerChanges() {
  masterOwner_.resize(contactPairs_.size());
  for (std::size_t p = 0; p < contactPairs_.size(); ++p) {
    const contact::ContactPair& pair = *contactPairs_[p];
    std::vector<int>& owners = masterOwner_[p];
    owners.resize(pair.itemCount(), -1);
    for (std::size_t item = 0; item < pair.itemCount(); ++item) {
      const int node = pair.masterNodeOf(item);
      const int owner = node >= 0 ? nodeOwner_[static_cast<std::size_t>(node)] : -1;
      if (owner >= 0 && owners[item] >= 0 && owner != owners[item]) ++masterOwnerChanges_;
      owners[item] = owner;
    }
  }
}

}  // namespace cc
