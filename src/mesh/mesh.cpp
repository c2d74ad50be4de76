// Small helpers of the Mesh data types: node counts and names of cell types, block lookup,
// node names for messages.
#include "mesh/mesh.hpp"

#include <fmt/format.h>

namespace cc {

int nodesPerCell(CellType type) {
  switch (type) {
    case CellType::Hex8:
      return 8;
    case CellType::Hex27:
      return 27;
    case CellType::Hex18:
      return 18;
    case CellType::Quad4:
      return 4;
    case CellType::Quad9:
      return 9;
  }
  return 0;
}

const char* toString(CellType type) {
  switch (type) {
    case CellType::Hex8:
      return "Hex8";
    case CellType::Hex27:
      return "Hex27";
    case CellType::Hex18:
      return "Hex18";
    case CellType::Quad4:
      return "Quad4";
    case CellType::Quad9:
      return "Quad9";
  }
  return "unknown";
}

const ElementBlock* Mesh::findBlock(const std::string& name) const {
  for (const ElementBlock& block : blocks) {
    if (block.name == name) return &block;
  }
  return nullptr;
}

std::string Mesh::nodeName(int node) const {
  const std::size_t index = static_cast<std::size_t>(node);
  return index < gmshNodeTags.size() ? fmt::format("gmsh node {}", gmshNodeTags[index])
                                     : fmt::format("node {}", node);
}

}  // namespace cc
