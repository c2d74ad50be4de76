// Model state beyond the displacement: the bodies (for the singular-system diagnosis) and the
// element and contact history saved for and restored by a restart.
#include <fmt/format.h>

#include <map>
#include <numeric>
#include <stdexcept>

#include "model/model.hpp"

namespace cc {

namespace {

// Union-find over nodes: elements join their nodes into one body.
class NodeGroups {
 public:
  explicit NodeGroups(int count) : parent_(count) { std::iota(parent_.begin(), parent_.end(), 0); }
  int root(int node) {
    while (parent_[node] != node) node = parent_[node] = parent_[parent_[node]];
    return node;
  }
  void join(int a, int b) { parent_[root(a)] = root(b); }

 private:
  std::vector<int> parent_;
};

template <class Named>
const Named* findNamed(const std::vector<std::pair<std::string, Named>>& entries,
                       const std::string& name) {
  for (const auto& [entryName, value] : entries) {
    if (entryName == name) return &value;
  }
  return nullptr;
}

}  // namespace

std::vector<BodyNodes> Model::bodies() const {
  const int numNodes = mesh_.numNodes();
  NodeGroups groups(numNodes);
  std::vector<bool> used(numNodes, false);
  for (const auto& set : elementSets_) {
    for (std::size_t item = 0; item < set->itemCount(); ++item) {
      const std::span<const int> nodes = set->itemNodes(item);
      for (int node : nodes) {
        used[node] = true;
        groups.join(node, nodes.front());
      }
    }
  }
  // Body names list the element sets that have elements in it, in deck order.
  std::map<int, std::size_t> bodyOfRoot;
  std::vector<BodyNodes> result;
  std::vector<std::vector<bool>> setsInBody;
  for (int node = 0; node < numNodes; ++node) {
    if (!used[node]) continue;
    const auto [it, added] = bodyOfRoot.try_emplace(groups.root(node), result.size());
    if (added) {
      result.emplace_back();
      setsInBody.emplace_back(elementSets_.size(), false);
    }
    result[it->second].nodes.push_back(node);
  }
  for (std::size_t s = 0; s < elementSets_.size(); ++s) {
    for (std::size_t item = 0; item < elementSets_[s]->itemCount(); ++item) {
      setsInBody[bodyOfRoot.at(groups.root(elementSets_[s]->itemNodes(item).front()))][s] = true;
    }
  }
  for (std::size_t b = 0; b < result.size(); ++b) {
    std::vector<std::string> names;
    for (std::size_t s = 0; s < elementSets_.size(); ++s) {
      if (setsInBody[b][s]) names.push_back(elementSets_[s]->name());
    }
    result[b].name = fmt::format("{}", fmt::join(names, "+"));
  }
  return result;
}

RestartRecord Model::saveHistory() const {
  RestartRecord history;
  for (const auto& set : elementSets_) {
    history.elementHistory.emplace_back(set->name(), set->exportHistory());
  }
  for (const auto& pair : contactPairs_) {
    history.contactHistory.emplace_back(pair->name(), pair->exportHistory());
  }
  return history;
}

void Model::restoreHistory(const RestartRecord& history) {
  if (history.displacement.size() != 3 * mesh_.numNodes()) {
    throw std::invalid_argument(fmt::format("the stored displacement has {} nodes, the model {}",
                                            history.displacement.size() / 3, mesh_.numNodes()));
  }
  for (auto& set : elementSets_) {
    const std::vector<double>* values = findNamed(history.elementHistory, set->name());
    if (!values) {
      throw std::invalid_argument(
          fmt::format("no stored history for element block '{}'", set->name()));
    }
    set->importHistory(*values);
  }
  for (auto& pair : contactPairs_) {
    const Eigen::MatrixXd* table = findNamed(history.contactHistory, pair->name());
    if (!table) {
      throw std::invalid_argument(
          fmt::format("no stored history for contact pair '{}'", pair->name()));
    }
    pair->importHistory(*table);
  }
  if (history.elementHistory.size() != elementSets_.size() ||
      history.contactHistory.size() != contactPairs_.size()) {
    throw std::invalid_argument(fmt::format(
        "the stored history has {} element blocks and {} contact pairs, the model {} and {}",
        history.elementHistory.size(), history.contactHistory.size(), elementSets_.size(),
        contactPairs_.size()));
  }
}

}  // namespace cc
