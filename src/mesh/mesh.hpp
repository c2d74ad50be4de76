// Mesh: reference node coordinates, volume element blocks, and named node and face sets, all
// taken from gmsh physical groups. Plain data; no element or contact knowledge lives here.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace cc {

// Node orderings follow gmsh, except SolidShell18 (built from Hex27 by dropping the mid-layer):
//   Hex8 : 0-3 bottom face (zeta=-1) counter-clockwise, 4-7 top face above them (gmsh order).
//   Hex27: gmsh order.
//   Hex18: 0-8 bottom biquadratic face, 9-17 top face, each in Quad9 order (corners 0-3
//          counter-clockwise, mid-edges 4-7 (edges 01,12,23,30), centre 8); zeta is thickness.
//   Quad4: corners counter-clockwise seen from outside the body (normal points outward).
//   Quad9: corners, mid-edges (01,12,23,30), centre; counter-clockwise seen from outside.
enum class CellType { Hex8, Hex27, Hex18, Quad4, Quad9 };

int nodesPerCell(CellType type);
// "Hex8", "Hex27", ...: the name in messages and in the results file's cell_type attributes
// (docs/output-format.md), so a change of it changes the file format.
const char* toString(CellType type);

using Connectivity = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Volume elements of one gmsh physical volume group.
struct ElementBlock {
  std::string name;
  CellType type = CellType::Hex8;
  Connectivity connectivity;                 // one row per element, 0-based node indices
  std::vector<std::size_t> gmshElementTags;  // per element, for messages; empty if not from gmsh
};

// Boundary faces of one gmsh physical surface group, each oriented with its normal pointing out
// of the volume element it bounds (so that a contact master normal points towards the slave).
struct FaceSet {
  std::string name;
  CellType type = CellType::Quad4;
  Connectivity connectivity;      // one row per face
  std::vector<int> ownerBlock;    // index into Mesh::blocks of the adjacent volume element
  std::vector<int> ownerElement;  // element index within that block
  std::vector<std::size_t> gmshElementTags;  // per face, for messages; empty if not from gmsh
};

struct NodeSet {
  std::string name;
  std::vector<int> nodes;  // sorted, unique, 0-based
};

struct Mesh {
  Eigen::Matrix3Xd coordinates;  // reference coordinates, one column per node
  std::vector<ElementBlock> blocks;
  std::map<std::string, FaceSet> faceSets;
  std::map<std::string, NodeSet> nodeSets;  // every physical group's nodes, and `all`
  std::vector<std::size_t> gmshNodeTags;    // per node, for messages; empty if not from gmsh

  int numNodes() const { return static_cast<int>(coordinates.cols()); }
  const ElementBlock* findBlock(const std::string& name) const;
  // How messages name a node: "gmsh node N" with the mesh file's tag, else "node N" (0-based).
  std::string nodeName(int node) const;
};

}  // namespace cc
