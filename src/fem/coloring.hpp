// Greedy coloring of a contribution's items so that no two items of one color share a node:
// the items of one color can be evaluated and scattered in parallel without locks or atomics.
#pragma once

#include <cstddef>
#include <vector>

#include "fem/contribution.hpp"

namespace cc {

struct ItemColoring {
  std::vector<std::size_t> items;       // item indices grouped by color, ascending within a color
  std::vector<std::size_t> colorBegin;  // color c holds items[colorBegin[c] .. colorBegin[c+1])
  std::size_t numColors() const { return colorBegin.empty() ? 0 : colorBegin.size() - 1; }
};

// First-fit coloring in item order. Throws std::out_of_range for a node index outside
// [0, numNodes) (a bug in the contribution, not a user error).
ItemColoring colorItems(const Contribution& contribution, int numNodes);

// Node -> items incidence in compressed rows: items of node n are items[offsets[n]..offsets[n+1]).
struct NodeIncidence {
  std::vector<std::size_t> offsets;
  std::vector<std::size_t> items;
};
// `keep` (optional) selects the items taken into account.
NodeIncidence nodeIncidence(const Contribution& contribution, int numNodes,
                            const std::function<bool(std::size_t item)>& keep = {});

}  // namespace cc
