// Lagrange shape functions on the reference quadrilateral [-1,1]^2 (Quad4, Quad9) and hexahedron
// [-1,1]^3 (Hex8, Hex27, Hex18) with first derivatives, and second derivatives on the surfaces.
#pragma once

#include <Eigen/Core>

// Every family has the same static interface, so element and contact code can be templates:
//   kNodes, kDim, Point, Values (N_a), Gradients (row a = dN_a/dxi_i),
//   values(xi), gradients(xi), nodeCoordinates() (column a = reference position of node a).
// The 2D families add SecondDerivatives (row a = N_a,11  N_a,22  N_a,12), needed for the
// surface derivatives rho_ij of eq. (14).
// Node orders follow gmsh (verified against gmsh::model::mesh::getElementProperties):
//   Quad4  corners counter-clockwise from (-1,-1).
//   Quad9  corners, mid-edges 01 12 23 30, centre.
//   Hex8   0-3 bottom (zeta = -1) counter-clockwise from (-1,-1,-1), 4-7 top above them.
//   Hex27  corners as Hex8; mid-edges 01 03 04 12 15 23 26 37 45 47 56 67; face centres
//          zeta=-1, eta=-1, xi=-1, xi=+1, eta=+1, zeta=+1; body centre.
//   Hex18  (not a gmsh type) Quad9 in (xi, eta) times linear in zeta: 0-8 the Quad9 nodes at
//          zeta = -1, 9-17 the same at zeta = +1.
namespace cc::shape {

struct Quad4 {
  static constexpr int kNodes = 4;
  static constexpr int kDim = 2;
  using Point = Eigen::Vector2d;
  using Values = Eigen::Matrix<double, kNodes, 1>;
  using Gradients = Eigen::Matrix<double, kNodes, kDim>;
  using SecondDerivatives = Eigen::Matrix<double, kNodes, 3>;
  static Values values(const Point& xi);
  static Gradients gradients(const Point& xi);
  static SecondDerivatives secondDerivatives(const Point& xi);
  static Eigen::Matrix<double, kDim, kNodes> nodeCoordinates();
};

struct Quad9 {
  static constexpr int kNodes = 9;
  static constexpr int kDim = 2;
  using Point = Eigen::Vector2d;
  using Values = Eigen::Matrix<double, kNodes, 1>;
  using Gradients = Eigen::Matrix<double, kNodes, kDim>;
  using SecondDerivatives = Eigen::Matrix<double, kNodes, 3>;
  static Values values(const Point& xi);
  static Gradients gradients(const Point& xi);
  static SecondDerivatives secondDerivatives(const Point& xi);
  static Eigen::Matrix<double, kDim, kNodes> nodeCoordinates();
};

struct Hex8 {
  static constexpr int kNodes = 8;
  static constexpr int kDim = 3;
  using Point = Eigen::Vector3d;
  using Values = Eigen::Matrix<double, kNodes, 1>;
  using Gradients = Eigen::Matrix<double, kNodes, kDim>;
  static Values values(const Point& xi);
  static Gradients gradients(const Point& xi);
  static Eigen::Matrix<double, kDim, kNodes> nodeCoordinates();
};

struct Hex27 {
  static constexpr int kNodes = 27;
  static constexpr int kDim = 3;
  using Point = Eigen::Vector3d;
  using Values = Eigen::Matrix<double, kNodes, 1>;
  using Gradients = Eigen::Matrix<double, kNodes, kDim>;
  static Values values(const Point& xi);
  static Gradients gradients(const Point& xi);
  static Eigen::Matrix<double, kDim, kNodes> nodeCoordinates();
};

struct Hex18 {
  static constexpr int kNodes = 18;
  static constexpr int kDim = 3;
  using Point = Eigen::Vector3d;
  using Values = Eigen::Matrix<double, kNodes, 1>;
  using Gradients = Eigen::Matrix<double, kNodes, kDim>;
  static Values values(const Point& xi);
  static Gradients gradients(const Point& xi);
  static Eigen::Matrix<double, kDim, kNodes> nodeCoordinates();
};

}  // namespace cc::shape
