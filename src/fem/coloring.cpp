// Greedy (first-fit) item coloring through the node -> item incidence: an item may not take a
// color already used by any item that shares one of its nodes.
#include "fem/coloring.hpp"

#include <stdexcept>
#include <string>

namespace cc {

namespace {

constexpr std::size_t kUncolored = static_cast<std::size_t>(-1);

void checkNode(const Contribution& contribution, std::size_t item, int node, int numNodes) {
  if (node < 0 || node >= numNodes) {
    throw std::out_of_range(contribution.name() + " item " + std::to_string(item) +
                            ": node index " + std::to_string(node) + " outside [0, " +
                            std::to_string(numNodes) + ")");
  }
}

}  // namespace

NodeIncidence nodeIncidence(const Contribution& contribution, int numNodes,
                            const std::function<bool(std::size_t item)>& keep) {
  NodeIncidence incidence;
  incidence.offsets.assign(static_cast<std::size_t>(numNodes) + 1, 0);
  const std::size_t numItems = contribution.itemCount();
  for (std::size_t item = 0; item < numItems; ++item) {
    if (keep && !keep(item)) continue;
    for (int node : contribution.itemNodes(item)) {
      checkNode(contribution, item, node, numNodes);
      ++incidence.offsets[static_cast<std::size_t>(node) + 1];
    }
  }
  for (std::size_t n = 0; n < static_cast<std::size_t>(numNodes); ++n) {
    incidence.offsets[n + 1] += incidence.offsets[n];
  }
  incidence.items.resize(incidence.offsets.back());
  std::vector<std::size_t> fill(incidence.offsets.begin(), incidence.offsets.end() - 1);
  for (std::size_t item = 0; item < numItems; ++item) {
    if (keep && !keep(item)) continue;
    for (int node : contribution.itemNodes(item)) incidence.items[fill[node]++] = item;
  }
  return incidence;
}

ItemColoring colorItems(const Contribution& contribution, int numNodes) {
  const NodeIncidence incidence = nodeIncidence(contribution, numNodes);
  const std::size_t numItems = contribution.itemCount();
  std::vector<std::size_t> color(numItems, kUncolored);
  // forbiddenFor[c] == item: color c is taken by a neighbour of `item` (marker, never cleared).
  std::vector<std::size_t> forbiddenFor;
  std::size_t numColors = 0;
  for (std::size_t item = 0; item < numItems; ++item) {
    for (int node : contribution.itemNodes(item)) {
      for (std::size_t k = incidence.offsets[node]; k < incidence.offsets[node + 1]; ++k) {
        const std::size_t neighbourColor = color[incidence.items[k]];
        if (neighbourColor != kUncolored) forbiddenFor[neighbourColor] = item;
      }
    }
    std::size_t chosen = 0;
    while (chosen < numColors && forbiddenFor[chosen] == item) ++chosen;
    if (chosen == numColors) {
      ++numColors;
      forbiddenFor.push_back(kUncolored);
    }
    color[item] = chosen;
  }

  ItemColoring coloring;
  coloring.colorBegin.assign(numColors + 1, 0);
  for (std::size_t item = 0; item < numItems; ++item) ++coloring.colorBegin[color[item] + 1];
  for (std::size_t c = 0; c < numColors; ++c) coloring.colorBegin[c + 1] += coloring.colorBegin[c];
  coloring.items.resize(numItems);
  std::vector<std::size_t> fill(coloring.colorBegin.begin(), coloring.colorBegin.end() - 1);
  for (std::size_t item = 0; item < numItems; ++item) coloring.items[fill[color[item]]++] = item;
  return coloring;
}

}  // namespace cc
