// Reference cells of the mesh module: local node coordinates (gmsh numbering; Hex18 as in
// mesh.hpp), shape functions and the outward faces of hexahedra, by CellType. Used for mesh checks
// and node reordering; the shape functions themselves are fem/shape_functions.hpp's.
#pragma once

#include <Eigen/Core>
#include <array>

#include "mesh/mesh.hpp"

namespace cc::cells {

// Local coordinates of `node` in [-1,1]^3 (2D cells: third coordinate 0).
Eigen::Vector3d localNode(CellType type, int node);

// The node of `type` at local coordinates `local` (exact lattice values -1, 0, 1); -1 if none.
int nodeAt(CellType type, const Eigen::Vector3d& local);

// Shape functions N_k(xi) and their local derivatives dN_k/dxi_i (row i, column k).
Eigen::VectorXd shapeValues(CellType type, const Eigen::Vector3d& xi);
Eigen::Matrix3Xd shapeGradients(CellType type, const Eigen::Vector3d& xi);

// det(dx/dxi) of a volume cell with node coordinates `nodes` (one column per node).
double jacobianDeterminant(CellType type, const Eigen::Matrix3Xd& nodes, const Eigen::Vector3d& xi);

// One face of a hexahedron in the cell's local numbering: corners counter-clockwise seen from
// outside (so the right-hand normal points out of a cell with positive Jacobian), the mid-edge
// nodes of edges 01, 12, 23, 30 of that corner order and the face centre (Quad9 order).
// For Hex8 midEdges and centre are -1.
struct HexFace {
  std::array<int, 4> corners;
  std::array<int, 4> midEdges;
  int centre;
};

// The six faces of a Hex8 or Hex27, in the order zeta=-1, eta=-1, xi=-1, xi=+1, eta=+1, zeta=+1
// (gmsh's order of the Hex27 face-centre nodes 20..25).
const std::array<HexFace, 6>& hexFaces(CellType type);

}  // namespace cc::cells
