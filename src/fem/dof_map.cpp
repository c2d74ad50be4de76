// DofMap construction: free equations first in node order (so the rows of a sparse column come
// out sorted when neighbour nodes are visited in order), prescribed dofs numbered separately.
#include "fem/dof_map.hpp"

#include <stdexcept>
#include <string>

namespace cc {

DofMap::DofMap(const std::vector<bool>& activeNodes, const std::vector<bool>& constrainedDofs) {
  const std::size_t numNodes = activeNodes.size();
  if (constrainedDofs.size() != 3 * numNodes) {
    throw std::invalid_argument("DofMap: " + std::to_string(constrainedDofs.size()) +
                                " constraint flags for " + std::to_string(numNodes) +
                                " nodes (expected 3 per node)");
  }
  index_.assign(3 * numNodes, kInactive);
  for (std::size_t node = 0; node < numNodes; ++node) {
    if (!activeNodes[node]) continue;
    for (std::size_t dof = 3 * node; dof < 3 * node + 3; ++dof) {
      if (constrainedDofs[dof]) {
        index_[dof] = -(numPrescribed_ + 2);
        prescribedDofs_.push_back(static_cast<int>(dof));
        ++numPrescribed_;
      } else {
        index_[dof] = numFree_;
        freeDofs_.push_back(static_cast<int>(dof));
        ++numFree_;
      }
    }
  }
}

}  // namespace cc
