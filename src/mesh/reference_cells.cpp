// Reference cells: node tables checked against gmsh's getElementProperties in the unit tests,
// shape functions as tensor products of 1D Lagrange polynomials on the nodes -1, 0, 1.
#include "mesh/reference_cells.hpp"

#include <Eigen/Dense>
#include <stdexcept>

namespace cc::cells {
namespace {

// gmsh's Hex27 node coordinates; the first 8 are the Hex8 corners.
constexpr int kHex27Nodes = 27;
constexpr double kHex27Local[kHex27Nodes][3] = {
    {-1, -1, -1}, {1, -1, -1}, {1, 1, -1},  {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1},
    {-1, 1, 1},   {0, -1, -1}, {-1, 0, -1}, {-1, -1, 0}, {1, 0, -1},  {1, -1, 0}, {0, 1, -1},
    {1, 1, 0},    {-1, 1, 0},  {0, -1, 1},  {-1, 0, 1},  {1, 0, 1},   {0, 1, 1},  {0, 0, -1},
    {0, -1, 0},   {-1, 0, 0},  {1, 0, 0},   {0, 1, 0},   {0, 0, 1},   {0, 0, 0}};

// gmsh's Quad9 node coordinates: corners, mid-edges 01, 12, 23, 30, centre; Quad4 = first 4.
constexpr int kQuad9Nodes = 9;
constexpr double kQuad9Local[kQuad9Nodes][2] = {{-1, -1}, {1, -1}, {1, 1},  {-1, 1}, {0, -1},
                                                {1, 0},   {0, 1},  {-1, 0}, {0, 0}};

// Polynomial degree along each local axis: the shape functions are products of 1D Lagrange
// polynomials of that degree (Hex18: biquadratic in the shell plane, linear in thickness).
Eigen::Vector3i axisDegrees(CellType type) {
  switch (type) {
    case CellType::Hex8:
      return {1, 1, 1};
    case CellType::Hex27:
      return {2, 2, 2};
    case CellType::Hex18:
      return {2, 2, 1};
    case CellType::Quad4:
      return {1, 1, 0};
    case CellType::Quad9:
      return {2, 2, 0};
  }
  return {0, 0, 0};
}

// 1D Lagrange polynomial of `degree` belonging to the node at `nodeCoordinate` (-1, 0 or 1)
// and its derivative, evaluated at x. Degree 0 is the constant 1 (unused third axis of quads).
Eigen::Vector2d lagrange1d(int degree, double nodeCoordinate, double x) {
  if (degree == 0) return {1.0, 0.0};
  if (degree == 1) return {0.5 * (1 + nodeCoordinate * x), 0.5 * nodeCoordinate};
  if (nodeCoordinate == 0) return {1 - x * x, -2 * x};
  return {0.5 * x * (x + nodeCoordinate), x + 0.5 * nodeCoordinate};
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
    case CellType::Hex27:
      return {kHex27Local[node][0], kHex27Local[node][1], kHex27Local[node][2]};
    case CellType::Hex18: {
      // Nodes 0-8: Quad9 at zeta = -1, nodes 9-17: the same Quad9 at zeta = +1.
      const int inPlane = node % kQuad9Nodes;
      const double zeta = node < kQuad9Nodes ? -1.0 : 1.0;
      return {kQuad9Local[inPlane][0], kQuad9Local[inPlane][1], zeta};
    }
    case CellType::Quad4:
    case CellType::Quad9:
      return {kQuad9Local[node][0], kQuad9Local[node][1], 0.0};
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
  const Eigen::Vector3i degrees = axisDegrees(type);
  Eigen::VectorXd values(nodesPerCell(type));
  for (int node = 0; node < values.size(); ++node) {
    const Eigen::Vector3d local = localNode(type, node);
    values(node) = 1.0;
    for (int axis = 0; axis < 3; ++axis) {
      values(node) *= lagrange1d(degrees(axis), local(axis), xi(axis))(0);
    }
  }
  return values;
}

Eigen::Matrix3Xd shapeGradients(CellType type, const Eigen::Vector3d& xi) {
  const Eigen::Vector3i degrees = axisDegrees(type);
  Eigen::Matrix3Xd gradients(3, nodesPerCell(type));
  for (int node = 0; node < gradients.cols(); ++node) {
    const Eigen::Vector3d local = localNode(type, node);
    Eigen::Matrix<double, 2, 3> factors;  // (value, derivative) of each axis' polynomial
    for (int axis = 0; axis < 3; ++axis) {
      factors.col(axis) = lagrange1d(degrees(axis), local(axis), xi(axis));
    }
    gradients(0, node) = factors(1, 0) * factors(0, 1) * factors(0, 2);
    gradients(1, node) = factors(0, 0) * factors(1, 1) * factors(0, 2);
    gradients(2, node) = factors(0, 0) * factors(0, 1) * factors(1, 2);
  }
  return gradients;
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
