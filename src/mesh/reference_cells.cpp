// Reference cells: the mesh module's view (by CellType) of the one shape-function implementation
// in fem/shape_functions.hpp, whose node tables the unit tests check against gmsh.
#include "mesh/reference_cells.hpp"

#include <Eigen/Dense>
#include <stdexcept>

#include "fem/shape_functions.hpp"

namespace cc::cells {
namespace {

// The reference cell's shape functions as a 3D evaluation: quads get a constant third axis.
template <class Family>
Eigen::VectorXd valuesOf(const Eigen::Vector3d& xi) {
  return Family::values(xi.head<Family::kDim>());
}
template <class Family>
Eigen::Matrix3Xd gradientsOf(const Eigen::Vector3d& xi) {
  Eigen::Matrix3Xd gradients = Eigen::Matrix3Xd::Zero(3, Family::kNodes);
  gradients.topRows<Family::kDim>() = Family::gradients(xi.head<Family::kDim>()).transpose();
  return gradients;
}
template <class Family>
Eigen::Vector3d nodeOf(int node) {
  Eigen::Vector3d local = Eigen::Vector3d::Zero();
  local.head<Family::kDim>() = Family::nodeCoordinates().col(node);
  return local;
}

std::array<HexFace, 6> buildHexFaces(CellType type) {
  // Corner quadruples counter-clockwise seen from outside, in gmsh's face order.
  constexpr int kCorners[6][4] = {{0, 3, 2, 1}, {0, 1, 5, 4}, {0, 4, 7, 3},
                                  {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}};
  std::array<HexFace, 6> faces{};
  for (int f = 0; f < 6; ++f) {
    HexFace& face = faces[f];
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int c = 0; c < 4; ++c) {
      face.corners[c] = kCorners[f][c];
      centre += 0.25 * localNode(CellType::Hex8, kCorners[f][c]);
    }
    const bool quadratic = type == CellType::Hex27;
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector3d mid =
          0.5 * (localNode(type, face.corners[c]) + localNode(type, face.corners[(c + 1) % 4]));
      face.midEdges[c] = quadratic ? nodeAt(type, mid) : -1;
    }
    face.centre = quadratic ? nodeAt(type, centre) : -1;
  }
  return faces;
}

}  // namespace

Eigen::Vector3d localNode(CellType type, int node) {
  if (node < 0 || node >= nodesPerCell(type)) throw std::out_of_range("cells::localNode");
  switch (type) {
    case CellType::Hex8:
      return nodeOf<shape::Hex8>(node);
    case CellType::Hex27:
      return nodeOf<shape::Hex27>(node);
    case CellType::Hex18:
      return nodeOf<shape::Hex18>(node);
    case CellType::Quad4:
      return nodeOf<shape::Quad4>(node);
    case CellType::Quad9:
      return nodeOf<shape::Quad9>(node);
  }
  return Eigen::Vector3d::Zero();
}

int nodeAt(CellType type, const Eigen::Vector3d& local) {
  for (int node = 0; node < nodesPerCell(type); ++node) {
    if (localNode(type, node) == local) return node;
  }
  return -1;
}

Eigen::VectorXd shapeValues(CellType type, const Eigen::Vector3d& xi) {
  switch (type) {
    case CellType::Hex8:
      return valuesOf<shape::Hex8>(xi);
    case CellType::Hex27:
      return valuesOf<shape::Hex27>(xi);
    case CellType::Hex18:
      return valuesOf<shape::Hex18>(xi);
    case CellType::Quad4:
      return valuesOf<shape::Quad4>(xi);
    case CellType::Quad9:
      return valuesOf<shape::Quad9>(xi);
  }
  return {};
}

Eigen::Matrix3Xd shapeGradients(CellType type, const Eigen::Vector3d& xi) {
  switch (type) {
    case CellType::Hex8:
      return gradientsOf<shape::Hex8>(xi);
    case CellType::Hex27:
      return gradientsOf<shape::Hex27>(xi);
    case CellType::Hex18:
      return gradientsOf<shape::Hex18>(xi);
    case CellType::Quad4:
      return gradientsOf<shape::Quad4>(xi);
    case CellType::Quad9:
      return gradientsOf<shape::Quad9>(xi);
  }
  return {};
}

double jacobianDeterminant(CellType type, const Eigen::Matrix3Xd& nodes,
                           const Eigen::Vector3d& xi) {
  const Eigen::Matrix3d jacobian = nodes * shapeGradients(type, xi).transpose();
  return jacobian.determinant();
}

const std::array<HexFace, 6>& hexFaces(CellType type) {
  static const std::array<HexFace, 6> hex8Faces = buildHexFaces(CellType::Hex8);
  static const std::array<HexFace, 6> hex27Faces = buildHexFaces(CellType::Hex27);
  if (type == CellType::Hex8) return hex8Faces;
  if (type == CellType::Hex27) return hex27Faces;
  throw std::invalid_argument("cells::hexFaces: only Hex8 and Hex27 have a face table");
}

}  // namespace cc::cells
