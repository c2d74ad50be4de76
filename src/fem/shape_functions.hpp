// Lagrange shape functions on the reference quadrilateral [-1,1]^2 (Quad4, Quad9) and hexahedron
// [-1,1]^3 (Hex8, Hex27, Hex18) with first derivatives, and second derivatives on the surfaces.
// The one implementation in the program: elements, contact segments (templated on the scalar type,
// so the exact contact tangent differentiates through the projection parameter xi) and the mesh
// module's reference cells all evaluate these.
#pragma once

#include <Eigen/Core>
#include <array>

// Every family has the same static interface, so element and contact code can be templates:
//   kNodes, kDim, Point, Values (N_a), Gradients (row a = dN_a/dxi_i),
//   values(xi), gradients(xi), nodeCoordinates() (column a = reference position of node a).
// The 2D families add SecondDerivatives (row a = N_a,11  N_a,12  N_a,22), needed for the
// surface derivatives rho_ij of eq. (14).
// Node orders follow gmsh (verified against gmsh::model::mesh::getElementProperties):
//   Quad4  corners counter-clockwise from (-1,-1).
//   Quad9  corners, mid-edges 01 12 23 30, centre.
//   Hex8   0-3 bottom (zeta = -1) counter-clockwise from (-1,-1,-1), 4-7 top above them.
//   Hex27  corners as Hex8; mid-edges 01 03 04 12 15 23 26 37 45 47 56 67; face centres
//          zeta=-1, eta=-1, xi=-1, xi=+1, eta=+1, zeta=+1; body centre.
//   Hex18  (not a gmsh type) Quad9 in (xi, eta) times linear in zeta: 0-8 the Quad9 nodes at
//          zeta = -1, 9-17 the same at zeta = +1.
// Each node is described by its 1D node index per direction (0 at -1, 1 at +1, 2 at the
// quadratic mid-node 0), so one tensor-product evaluation serves every family and the node tables
// read like the gmsh reference elements.
namespace cc::shape {

namespace detail {

inline constexpr std::array<double, 3> kNode1DPosition = {-1.0, 1.0, 0.0};

// Values and first/second derivatives of the 1D Lagrange basis of the given degree (1 or 2).
template <class Scalar>
struct Basis1D {
  std::array<Scalar, 3> value{};
  std::array<Scalar, 3> first{};
  std::array<Scalar, 3> second{};
};

template <class Scalar>
Basis1D<Scalar> basis1D(int degree, const Scalar& x) {
  Basis1D<Scalar> b;
  b.value = {Scalar(0.0), Scalar(0.0), Scalar(0.0)};
  b.first = b.value;
  b.second = b.value;
  if (degree == 1) {
    b.value = {0.5 * (1.0 - x), 0.5 * (1.0 + x), Scalar(0.0)};
    b.first = {Scalar(-0.5), Scalar(0.5), Scalar(0.0)};
  } else {
    b.value = {0.5 * x * (x - 1.0), 0.5 * x * (x + 1.0), 1.0 - x * x};
    b.first = {x - 0.5, x + 0.5, -2.0 * x};
    b.second = {Scalar(1.0), Scalar(1.0), Scalar(-2.0)};
  }
  return b;
}

template <int Nodes, int Dim>
using NodeTable = std::array<std::array<int, Dim>, Nodes>;

// Tables laid out one row per node group; the formatter would spread them one node per line.
// clang-format off
inline constexpr NodeTable<4, 2> kQuad4Nodes = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
inline constexpr NodeTable<9, 2> kQuad9Nodes = {{
    {0, 0}, {1, 0}, {1, 1}, {0, 1},  // corners
    {2, 0}, {1, 2}, {2, 1}, {0, 2},  // mid-edges 01 12 23 30
    {2, 2}}};                        // centre
inline constexpr NodeTable<8, 3> kHex8Nodes = {{
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},   // bottom, zeta = -1
    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};  // top, zeta = +1
inline constexpr NodeTable<27, 3> kHex27Nodes = {{
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1},
    {2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {1, 2, 0}, {1, 0, 2}, {2, 1, 0},  // edges 01 03 04 12 15 23
    {1, 1, 2}, {0, 1, 2}, {2, 0, 1}, {0, 2, 1}, {1, 2, 1}, {2, 1, 1},  // edges 26 37 45 47 56 67
    {2, 2, 0}, {2, 0, 2}, {0, 2, 2}, {1, 2, 2}, {2, 1, 2}, {2, 2, 1},  // face centres
    {2, 2, 2}}};                                                       // body centre
inline constexpr NodeTable<18, 3> kHex18Nodes = {{
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {1, 2, 0}, {2, 1, 0}, {0, 2, 0},
    {2, 2, 0},                                                          // Quad9 at zeta = -1
    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {2, 0, 1}, {1, 2, 1}, {2, 1, 1}, {0, 2, 1},
    {2, 2, 1}}};                                                        // Quad9 at zeta = +1
// clang-format on

// Product over directions; direction d contributes its derivative of order derivOrder[d].
template <class Scalar, int Dim>
Scalar product(const std::array<Basis1D<Scalar>, Dim>& b, const std::array<int, Dim>& node,
               const std::array<int, Dim>& derivOrder) {
  Scalar result = Scalar(1.0);
  for (int d = 0; d < Dim; ++d) {
    const Basis1D<Scalar>& basis = b[d];
    const int k = node[d];
    result *= derivOrder[d] == 0 ? basis.value[k]
                                 : (derivOrder[d] == 1 ? basis.first[k] : basis.second[k]);
  }
  return result;
}

template <class Scalar, int Dim>
std::array<Basis1D<Scalar>, Dim> bases(const std::array<int, Dim>& degree,
                                       const std::array<Scalar, Dim>& xi) {
  std::array<Basis1D<Scalar>, Dim> result;
  for (int d = 0; d < Dim; ++d) result[d] = basis1D(degree[d], xi[d]);
  return result;
}

// A family: its node table and the polynomial degree along each axis.
template <int Nodes, int Dim>
struct TensorFamily {
  const NodeTable<Nodes, Dim>& nodes;
  std::array<int, Dim> degree;

  Eigen::Matrix<double, Nodes, 1> values(const Eigen::Matrix<double, Dim, 1>& xi) const {
    const auto b = bases<double, Dim>(degree, toArray(xi));
    Eigen::Matrix<double, Nodes, 1> n;
    for (int a = 0; a < Nodes; ++a) n[a] = product<double, Dim>(b, nodes[a], {});
    return n;
  }

  Eigen::Matrix<double, Nodes, Dim> gradients(const Eigen::Matrix<double, Dim, 1>& xi) const {
    const auto b = bases<double, Dim>(degree, toArray(xi));
    Eigen::Matrix<double, Nodes, Dim> dn;
    for (int a = 0; a < Nodes; ++a) {
      for (int i = 0; i < Dim; ++i) {
        std::array<int, Dim> order{};
        order[i] = 1;
        dn(a, i) = product<double, Dim>(b, nodes[a], order);
      }
    }
    return dn;
  }

  Eigen::Matrix<double, Dim, Nodes> nodeCoordinates() const {
    Eigen::Matrix<double, Dim, Nodes> coordinates;
    for (int a = 0; a < Nodes; ++a) {
      for (int d = 0; d < Dim; ++d) coordinates(d, a) = kNode1DPosition[nodes[a][d]];
    }
    return coordinates;
  }

  static std::array<double, Dim> toArray(const Eigen::Matrix<double, Dim, 1>& xi) {
    std::array<double, Dim> a;
    for (int d = 0; d < Dim; ++d) a[d] = xi[d];
    return a;
  }
};

inline constexpr TensorFamily<4, 2> kQuad4{kQuad4Nodes, {1, 1}};
inline constexpr TensorFamily<9, 2> kQuad9{kQuad9Nodes, {2, 2}};
inline constexpr TensorFamily<8, 3> kHex8{kHex8Nodes, {1, 1, 1}};
inline constexpr TensorFamily<27, 3> kHex27{kHex27Nodes, {2, 2, 2}};
inline constexpr TensorFamily<18, 3> kHex18{kHex18Nodes, {2, 2, 1}};

}  // namespace detail

// Surface segments for contact (and anything needing second derivatives), on any scalar type.
enum class SurfaceType { Quad4, Quad9 };

constexpr int surfaceNodes(SurfaceType type) {
  return type == SurfaceType::Quad4 ? 4 : 9;
}

// Values N_k, first derivatives N_k,i and second derivatives N_k,ij (i,j = xi^1, xi^2) of a
// surface segment's shape functions. Eq. (1): rho = N_k(xi) x^(k).
template <class Scalar>
struct SurfaceShape {
  static constexpr int kMaxNodes = 9;
  int count = 0;
  std::array<Scalar, kMaxNodes> value{};
  std::array<std::array<Scalar, 2>, kMaxNodes> first{};   // [k][i] = dN_k / dxi^i
  std::array<std::array<Scalar, 3>, kMaxNodes> second{};  // [k][0,1,2] = N_k,11  N_k,12  N_k,22
};

template <class Scalar>
SurfaceShape<Scalar> surfaceShape(SurfaceType type, const Scalar& xi1, const Scalar& xi2) {
  const bool linear = type == SurfaceType::Quad4;
  const std::array<int, 2> degree = linear ? std::array<int, 2>{1, 1} : std::array<int, 2>{2, 2};
  const auto b = detail::bases<Scalar, 2>(degree, {xi1, xi2});
  SurfaceShape<Scalar> shape;
  shape.count = surfaceNodes(type);
  for (int k = 0; k < shape.count; ++k) {
    const std::array<int, 2>& node = linear ? detail::kQuad4Nodes[k] : detail::kQuad9Nodes[k];
    shape.value[k] = detail::product<Scalar, 2>(b, node, {0, 0});
    shape.first[k] = {detail::product<Scalar, 2>(b, node, {1, 0}),
                      detail::product<Scalar, 2>(b, node, {0, 1})};
    shape.second[k] = {detail::product<Scalar, 2>(b, node, {2, 0}),
                       detail::product<Scalar, 2>(b, node, {1, 1}),
                       detail::product<Scalar, 2>(b, node, {0, 2})};
  }
  return shape;
}

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
