// Hex27 -> Hex18 conversion for 18-node solid-shells and thickness-axis reordering of hexahedra.
// Both work on local node coordinates (reference_cells), so no node table is written twice.
#include "mesh/hex18.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <stdexcept>

#include "mesh/reference_cells.hpp"

namespace cc {
namespace {

ElementBlock& blockAt(Mesh& mesh, int blockIndex, const char* caller) {
  if (blockIndex < 0 || blockIndex >= static_cast<int>(mesh.blocks.size())) {
    throw std::invalid_argument(fmt::format("{}: block index {} out of range", caller, blockIndex));
  }
  return mesh.blocks[blockIndex];
}

// Removes from every node set the `candidates` that no element of any block uses any more.
void removeOrphansFromNodeSets(Mesh& mesh, const std::vector<bool>& candidates) {
  std::vector<bool> used(mesh.numNodes(), false);
  for (const ElementBlock& block : mesh.blocks) {
    for (int node : block.connectivity.reshaped()) used[node] = true;
  }
  for (auto& [name, set] : mesh.nodeSets) {
    std::erase_if(set.nodes, [&](int node) { return candidates[node] && !used[node]; });
  }
}

// The signed permutation of local axes that makes old local axis `axis` (times `sign`) the new
// zeta axis; a cyclic permutation with an even number of sign flips, so its determinant is +1.
Eigen::Matrix3d thicknessRotation(int axis, double sign) {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Zero();
  rotation(0, (axis + 1) % 3) = sign;
  rotation(1, (axis + 2) % 3) = 1.0;
  rotation(2, axis) = sign;
  return rotation;
}

// newNode -> oldNode: new node k sits at the old local point rotation^T * localNode(k).
std::vector<int> rotatedNodeOrder(CellType type, const Eigen::Matrix3d& rotation) {
  std::vector<int> order(nodesPerCell(type));
  for (int node = 0; node < nodesPerCell(type); ++node) {
    order[node] = cells::nodeAt(type, rotation.transpose() * cells::localNode(type, node));
  }
  return order;
}

}  // namespace

void convertToSolidShell18(Mesh& mesh, int blockIndex) {
  ElementBlock& block = blockAt(mesh, blockIndex, "convertToSolidShell18");
  if (block.type != CellType::Hex27) {
    throw std::invalid_argument(fmt::format("convertToSolidShell18: block '{}' is {}, not Hex27",
                                            block.name, toString(block.type)));
  }
  constexpr int kShellNodes = 18;
  constexpr int kSolidNodes = 27;
  std::array<int, kShellNodes> solidNodeOf{};  // the Hex27 node at each Hex18 node's position
  std::array<bool, kSolidNodes> kept{};
  for (int node = 0; node < kShellNodes; ++node) {
    solidNodeOf[node] = cells::nodeAt(CellType::Hex27, cells::localNode(CellType::Hex18, node));
    kept[solidNodeOf[node]] = true;
  }
  std::vector<bool> dropped(mesh.numNodes(), false);
  Connectivity shell(block.connectivity.rows(), kShellNodes);
  for (Eigen::Index e = 0; e < block.connectivity.rows(); ++e) {
    for (int node = 0; node < kShellNodes; ++node)
      shell(e, node) = block.connectivity(e, solidNodeOf[node]);
    for (int node = 0; node < kSolidNodes; ++node) {
      if (!kept[node]) dropped[block.connectivity(e, node)] = true;
    }
  }
  block.connectivity = std::move(shell);
  block.type = CellType::Hex18;
  removeOrphansFromNodeSets(mesh, dropped);
}

void orientThickness(Mesh& mesh, int blockIndex, int globalAxis) {
  ElementBlock& block = blockAt(mesh, blockIndex, "orientThickness");
  if (block.type != CellType::Hex8 && block.type != CellType::Hex27) {
    throw std::invalid_argument(fmt::format("orientThickness: block '{}' is {}, not Hex8/Hex27",
                                            block.name, toString(block.type)));
  }
  if (globalAxis < 0 || globalAxis > 2) {
    throw std::invalid_argument(
        fmt::format("orientThickness: axis {} is not 0, 1 or 2", globalAxis));
  }
  const int nodeCount = nodesPerCell(block.type);
  const Eigen::Matrix3Xd centreGradients =
      cells::shapeGradients(block.type, Eigen::Vector3d::Zero());
  std::array<std::vector<int>, 6> orders;  // per (local axis, sign): new -> old local node
  for (int axis = 0; axis < 3; ++axis) {
    orders[2 * axis] = rotatedNodeOrder(block.type, thicknessRotation(axis, 1.0));
    orders[2 * axis + 1] = rotatedNodeOrder(block.type, thicknessRotation(axis, -1.0));
  }
  for (Eigen::Index e = 0; e < block.connectivity.rows(); ++e) {
    Eigen::Matrix3Xd nodes(3, nodeCount);
    for (int k = 0; k < nodeCount; ++k)
      nodes.col(k) = mesh.coordinates.col(block.connectivity(e, k));
    // Column i: the covariant base vector dx/dxi_i at the element centre.
    const Eigen::Matrix3d jacobian = nodes * centreGradients.transpose();
    int bestAxis = 0;
    double bestCosine = -1.0;
    for (int axis = 0; axis < 3; ++axis) {
      const double cosine = std::abs(jacobian(globalAxis, axis)) / jacobian.col(axis).norm();
      if (cosine > bestCosine) {
        bestCosine = cosine;
        bestAxis = axis;
      }
    }
    const bool flip = jacobian(globalAxis, bestAxis) < 0;
    const std::vector<int>& order = orders[2 * bestAxis + (flip ? 1 : 0)];
    const Eigen::RowVectorXi oldRow = block.connectivity.row(e);
    for (int k = 0; k < nodeCount; ++k) block.connectivity(e, k) = oldRow(order[k]);
  }
}

}  // namespace cc
