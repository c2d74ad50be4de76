// Small helpers of the Mesh data types: node counts and names of cell types, block lookup.
#include "mesh/mesh.hpp"

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

}  // namespace cc
