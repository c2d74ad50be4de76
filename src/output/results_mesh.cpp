// Mesh group of the results file: /mesh/coordinates, /mesh/blocks/*, /mesh/node_sets/*,
// /mesh/face_sets/*, plus the VTK-ordered connectivity for blocks ParaView cannot draw as stored.
#include "output/results_mesh.hpp"

#include "output/results_layout.hpp"
#include "spec/problem_spec.hpp"

namespace cc {

namespace {

using RowMajorInts = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// gmsh Hex27 index of each VTK_TRIQUADRATIC_HEXAHEDRON node: corners; mid-edges 01,12,23,30,
// 45,56,67,74,04,15,26,37; face centres x-,x+,y-,y+,z-,z+; body centre (vtkTriQuadraticHexahedron
// parametric coordinates against gmsh's Hexahedron27 numbering).
const std::vector<int> kVtkFromGmshHex27 = {0,  1,  2,  3,  4,  5,  6,  7,  8,  11, 13, 9,  16, 18,
                                            19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25, 26};
// Hex18 corners: bottom Quad9 corners 0-3 and top Quad9 corners 9-12 (see mesh.hpp).
const std::vector<int> kHex18Corners = {0, 1, 2, 3, 9, 10, 11, 12};

const char* xdmfTopology(CellType type) {
  return type == CellType::Hex27 ? "Hexahedron_27" : "Hexahedron";
}

void writeConnectivity(h5::FileRef file, hid_t group, const char* name, const Connectivity& rows) {
  h5::writeInts(file, group, name, rows.data(), static_cast<hsize_t>(rows.rows()),
                static_cast<hsize_t>(rows.cols()));
}

XdmfBlock writeBlock(h5::FileRef file, hid_t blocksGroup, const ElementBlock& block, int index,
                     long firstElement) {
  const std::string link = layout::linkName(block.name);
  h5::Group group = h5::createGroup(file, blocksGroup, link);
  h5::writeAttribute(file, group.get(), "name", block.name);
  h5::writeAttribute(file, group.get(), "cell_type", std::string(toString(block.type)));
  h5::writeAttribute(file, group.get(), "index", index);
  h5::writeAttribute(file, group.get(), "first_element", static_cast<int>(firstElement));
  writeConnectivity(file, group.get(), "connectivity", block.connectivity);

  const std::string blockPath = std::string(layout::kBlocksGroup) + "/" + link;
  XdmfBlock visual{block.name,
                   xdmfTopology(block.type),
                   static_cast<long>(block.connectivity.rows()),
                   static_cast<int>(block.connectivity.cols()),
                   blockPath + "/connectivity",
                   firstElement};
  const std::vector<int> order = visualNodeOrder(block.type);
  if (!order.empty()) {
    RowMajorInts reordered(block.connectivity.rows(), static_cast<Eigen::Index>(order.size()));
    for (Eigen::Index column = 0; column < reordered.cols(); ++column)
      reordered.col(column) = block.connectivity.col(order[static_cast<size_t>(column)]);
    writeConnectivity(file, group.get(), "visual_connectivity", reordered);
    visual.nodesPerCell = static_cast<int>(order.size());
    visual.connectivityPath = blockPath + "/visual_connectivity";
  }
  return visual;
}

void writeSets(h5::FileRef file, hid_t meshGroup, const Mesh& mesh) {
  h5::Group nodeSets = h5::createGroup(file, meshGroup, "node_sets");
  for (const auto& [name, set] : mesh.nodeSets) {
    // The built-in set `all` is every node 0..N-1: it says nothing the coordinates do not, and
    // would add one integer per node to every results file.
    if (name == kAllNodesSet) continue;
    h5::Group group = h5::createGroup(file, nodeSets.get(), layout::linkName(name));
    h5::writeAttribute(file, group.get(), "name", name);
    h5::writeInts(file, group.get(), "nodes", set.nodes.data(), set.nodes.size(), 0);
  }
  h5::Group faceSets = h5::createGroup(file, meshGroup, "face_sets");
  for (const auto& [name, set] : mesh.faceSets) {
    h5::Group group = h5::createGroup(file, faceSets.get(), layout::linkName(name));
    h5::writeAttribute(file, group.get(), "name", name);
    h5::writeAttribute(file, group.get(), "cell_type", std::string(toString(set.type)));
    writeConnectivity(file, group.get(), "connectivity", set.connectivity);
    h5::writeInts(file, group.get(), "owner_block", set.ownerBlock.data(), set.ownerBlock.size(),
                  0);
    h5::writeInts(file, group.get(), "owner_element", set.ownerElement.data(),
                  set.ownerElement.size(), 0);
  }
}

}  // namespace

std::vector<int> visualNodeOrder(CellType type) {
  if (type == CellType::Hex27) return kVtkFromGmshHex27;
  if (type == CellType::Hex18) return kHex18Corners;
  return {};
}

std::vector<XdmfBlock> writeMesh(h5::FileRef file, const Mesh& mesh) {
  h5::Group meshGroup = h5::createGroup(file, file.id, "mesh");
  h5::writeDoubles(file, meshGroup.get(), "coordinates", mesh.coordinates.data(),
                   static_cast<hsize_t>(mesh.numNodes()), 3);
  h5::Group blocks = h5::createGroup(file, meshGroup.get(), "blocks");
  std::vector<XdmfBlock> visualBlocks;
  std::vector<std::string> blockNames;
  long firstElement = 0;
  for (size_t index = 0; index < mesh.blocks.size(); ++index) {
    const ElementBlock& block = mesh.blocks[index];
    visualBlocks.push_back(
        writeBlock(file, blocks.get(), block, static_cast<int>(index), firstElement));
    blockNames.push_back(block.name);
    firstElement += static_cast<long>(block.connectivity.rows());
  }
  h5::writeAttribute(file, blocks.get(), "names", blockNames);
  h5::writeAttribute(file, meshGroup.get(), "num_nodes", mesh.numNodes());
  h5::writeAttribute(file, meshGroup.get(), "num_elements", static_cast<int>(firstElement));
  writeSets(file, meshGroup.get(), mesh);
  return visualBlocks;
}

}  // namespace cc
