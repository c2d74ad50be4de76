// Node graph and compressed-column pattern construction. Memory stays O(nonzeros): node
// incidence lists per contribution (two on several processes) and a marker array, never
// per-item index maps.
#include "fem/sparsity_pattern.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "fem/coloring.hpp"

namespace cc {

NodeGraph buildNodeGraph(std::span<Contribution* const> contributions, int numNodes,
                         const ItemFilter& filter, std::span<const char> ownedNodes) {
  // Items this process adds (all of them, or those the filter assembles), and on several
  // processes the others' items with a node here: their entries in this process's rows.
  std::vector<NodeIncidence> incidences, othersIncidences;
  incidences.reserve(contributions.size());
  const bool completeOwnedRows = !ownedNodes.empty() && filter;
  const auto touchesOwned = [&](const Contribution& contribution, std::size_t item) {
    for (int node : contribution.itemNodes(item)) {
      if (ownedNodes[static_cast<std::size_t>(node)]) return true;
    }
    return false;
  };
  for (std::size_t c = 0; c < contributions.size(); ++c) {
    std::function<bool(std::size_t)> assembled;
    if (filter)
      assembled = [&filter, c](std::size_t item) { return filter(c, item) == ItemRole::Assemble; };
    incidences.push_back(nodeIncidence(*contributions[c], numNodes, assembled));
    if (!completeOwnedRows) continue;
    const Contribution& contribution = *contributions[c];
    othersIncidences.push_back(nodeIncidence(
        contribution, numNodes, [&filter, &touchesOwned, &contribution, c](std::size_t item) {
          return filter(c, item) != ItemRole::Assemble && touchesOwned(contribution, item);
        }));
  }
  NodeGraph graph;
  graph.offsets.assign(static_cast<std::size_t>(numNodes) + 1, 0);
  std::vector<int> lastSeenBy(static_cast<std::size_t>(numNodes), -1);
  for (int node = 0; node < numNodes; ++node) {
    const std::size_t first = graph.neighbours.size();
    graph.neighbours.push_back(node);
    lastSeenBy[node] = node;
    const auto addNodesOf = [&](const NodeIncidence& incidence, const Contribution& contribution,
                                bool ownedOnly) {
      for (std::size_t k = incidence.offsets[node]; k < incidence.offsets[node + 1]; ++k) {
        for (int neighbour : contribution.itemNodes(incidence.items[k])) {
          if (lastSeenBy[neighbour] == node) continue;
          if (ownedOnly && !ownedNodes[static_cast<std::size_t>(neighbour)]) continue;
          lastSeenBy[neighbour] = node;
          graph.neighbours.push_back(neighbour);
        }
      }
    };
    for (std::size_t c = 0; c < contributions.size(); ++c) {
      addNodesOf(incidences[c], *contributions[c], false);
      if (completeOwnedRows) addNodesOf(othersIncidences[c], *contributions[c], true);
    }
    std::sort(graph.neighbours.begin() + static_cast<std::ptrdiff_t>(first),
              graph.neighbours.end());
    graph.offsets[node + 1] = static_cast<std::int64_t>(graph.neighbours.size());
  }
  return graph;
}

namespace {

// Rows of one column: the free equations of the column node's neighbours, ascending.
template <typename RowVisitor>
void visitRows(const DofMap& dofs, const NodeGraph& graph, int node, RowVisitor&& visit) {
  for (std::int64_t k = graph.offsets[node]; k < graph.offsets[node + 1]; ++k) {
    const int neighbour = graph.neighbours[k];
    for (int component = 0; component < 3; ++component) {
      const int row = dofs.equation(3 * neighbour + component);
      if (row >= 0) visit(row);
    }
  }
}

// Fills one block: column j belongs to dof columnDofs[j].
void fillBlock(const DofMap& dofs, const NodeGraph& graph, const std::vector<int>& columnDofs,
               SparseMatrix& block) {
  const int numColumns = static_cast<int>(columnDofs.size());
  std::vector<int> columnStart(static_cast<std::size_t>(numColumns) + 1, 0);
  std::int64_t nonZeros = 0;
  for (int j = 0; j < numColumns; ++j) {
    visitRows(dofs, graph, columnDofs[j] / 3, [&](int) { ++nonZeros; });
    if (nonZeros > std::numeric_limits<int>::max()) {
      throw std::length_error("sparsity pattern exceeds 2^31 nonzeros (int indices)");
    }
    columnStart[j + 1] = static_cast<int>(nonZeros);
  }
  block.resize(dofs.numFree(), numColumns);
  block.resizeNonZeros(static_cast<Eigen::Index>(nonZeros));
  std::copy(columnStart.begin(), columnStart.end(), block.outerIndexPtr());
  int* rows = block.innerIndexPtr();
  for (int j = 0; j < numColumns; ++j) {
    int position = columnStart[j];
    visitRows(dofs, graph, columnDofs[j] / 3, [&](int row) { rows[position++] = row; });
  }
  std::fill(block.valuePtr(), block.valuePtr() + nonZeros, 0.0);
}

}  // namespace

void buildSparsityPattern(const DofMap& dofs, const NodeGraph& graph, SparseMatrix& free,
                          SparseMatrix& coupling) {
  fillBlock(dofs, graph, dofs.freeDofs(), free);
  fillBlock(dofs, graph, dofs.prescribedDofs(), coupling);
}

bool samePattern(const SparseMatrix& a, const SparseMatrix& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  if (!a.isCompressed() || !b.isCompressed()) return false;
  return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}

}  // namespace cc
