// Shape functions as tensor products of 1D Lagrange bases: each node is described by its 1D node
// index per direction (0 at -1, 1 at +1, 2 at the quadratic mid-node 0), so one generic
// evaluation serves every family and the node tables read like the gmsh reference elements.
#include "fem/shape_functions.hpp"

#include <array>

namespace cc::shape {
namespace {

constexpr int kMaxBasis1D = 3;
constexpr std::array<double, kMaxBasis1D> kNode1DPosition = {-1.0, 1.0, 0.0};

// Values and first/second derivatives of the 1D Lagrange basis of the given degree (1 or 2).
struct Basis1D {
  std::array<double, kMaxBasis1D> value{};
  std::array<double, kMaxBasis1D> first{};
  std::array<double, kMaxBasis1D> second{};
};

Basis1D basis1D(int degree, double x) {
  Basis1D b;
  if (degree == 1) {
    b.value = {0.5 * (1.0 - x), 0.5 * (1.0 + x), 0.0};
    b.first = {-0.5, 0.5, 0.0};
  } else {
    b.value = {0.5 * x * (x - 1.0), 0.5 * x * (x + 1.0), 1.0 - x * x};
    b.first = {x - 0.5, x + 0.5, -2.0 * x};
    b.second = {1.0, 1.0, -2.0};
  }
  return b;
}

template <int Nodes, int Dim>
using NodeTable = std::array<std::array<int, Dim>, Nodes>;

template <int Nodes, int Dim>
struct TensorFamily {
  const NodeTable<Nodes, Dim>& nodes;
  std::array<int, Dim> degree;

  std::array<Basis1D, Dim> bases(const Eigen::Matrix<double, Dim, 1>& xi) const {
    std::array<Basis1D, Dim> result;
    for (int d = 0; d < Dim; ++d) result[d] = basis1D(degree[d], xi[d]);
    return result;
  }

  // Product over directions; direction d contributes its derivative of order derivOrder[d].
  static double product(const std::array<Basis1D, Dim>& b, const std::array<int, Dim>& node,
                        const std::array<int, Dim>& derivOrder) {
    double result = 1.0;
    for (int d = 0; d < Dim; ++d) {
      const Basis1D& basis = b[d];
      const int k = node[d];
      result *= derivOrder[d] == 0 ? basis.value[k]
                                   : (derivOrder[d] == 1 ? basis.first[k] : basis.second[k]);
    }
    return result;
  }

  Eigen::Matrix<double, Nodes, 1> values(const Eigen::Matrix<double, Dim, 1>& xi) const {
    const auto b = bases(xi);
    Eigen::Matrix<double, Nodes, 1> n;
    for (int a = 0; a < Nodes; ++a) n[a] = product(b, nodes[a], {});
    return n;
  }

  Eigen::Matrix<double, Nodes, Dim> gradients(const Eigen::Matrix<double, Dim, 1>& xi) const {
    const auto b = bases(xi);
    Eigen::Matrix<double, Nodes, Dim> dn;
    for (int a = 0; a < Nodes; ++a) {
      for (int i = 0; i < Dim; ++i) {
        std::array<int, Dim> order{};
        order[i] = 1;
        dn(a, i) = product(b, nodes[a], order);
      }
    }
    return dn;
  }

  // Columns: N,11  N,22  N,12 (2D only).
  Eigen::Matrix<double, Nodes, 3> secondDerivatives(const Eigen::Vector2d& xi) const {
    static_assert(Dim == 2, "second derivatives are provided for surface families");
    const auto b = bases(xi);
    Eigen::Matrix<double, Nodes, 3> ddn;
    for (int a = 0; a < Nodes; ++a) {
      ddn(a, 0) = product(b, nodes[a], {2, 0});
      ddn(a, 1) = product(b, nodes[a], {0, 2});
      ddn(a, 2) = product(b, nodes[a], {1, 1});
    }
    return ddn;
  }

  Eigen::Matrix<double, Dim, Nodes> nodeCoordinates() const {
    Eigen::Matrix<double, Dim, Nodes> coordinates;
    for (int a = 0; a < Nodes; ++a) {
      for (int d = 0; d < Dim; ++d) coordinates(d, a) = kNode1DPosition[nodes[a][d]];
    }
    return coordinates;
  }
};

// Tables laid out one row per node group; the formatter would spread them one node per line.
// clang-format off
constexpr NodeTable<4, 2> kQuad4Nodes = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
constexpr NodeTable<9, 2> kQuad9Nodes = {{
    {0, 0}, {1, 0}, {1, 1}, {0, 1},  // corners
    {2, 0}, {1, 2}, {2, 1}, {0, 2},  // mid-edges 01 12 23 30
    {2, 2}}};                        // centre
constexpr NodeTable<8, 3> kHex8Nodes = {{
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},   // bottom, zeta = -1
    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};  // top, zeta = +1
constexpr NodeTable<27, 3> kHex27Nodes = {{
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1},
    {2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {1, 2, 0}, {1, 0, 2}, {2, 1, 0},  // edges 01 03 04 12 15 23
    {1, 1, 2}, {0, 1, 2}, {2, 0, 1}, {0, 2, 1}, {1, 2, 1}, {2, 1, 1},  // edges 26 37 45 47 56 67
    {2, 2, 0}, {2, 0, 2}, {0, 2, 2}, {1, 2, 2}, {2, 1, 2}, {2, 2, 1},  // face centres
    {2, 2, 2}}};                                                       // body centre
constexpr NodeTable<18, 3> kHex18Nodes = {{
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {1, 2, 0}, {2, 1, 0}, {0, 2, 0},
    {2, 2, 0},                                                          // Quad9 at zeta = -1
    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, {2, 0, 1}, {1, 2, 1}, {2, 1, 1}, {0, 2, 1},
    {2, 2, 1}}};                                                        // Quad9 at zeta = +1
// clang-format on

constexpr TensorFamily<4, 2> kQuad4{kQuad4Nodes, {1, 1}};
constexpr TensorFamily<9, 2> kQuad9{kQuad9Nodes, {2, 2}};
constexpr TensorFamily<8, 3> kHex8{kHex8Nodes, {1, 1, 1}};
constexpr TensorFamily<27, 3> kHex27{kHex27Nodes, {2, 2, 2}};
constexpr TensorFamily<18, 3> kHex18{kHex18Nodes, {2, 2, 1}};

}  // namespace

Quad4::Values Quad4::values(const Point& xi) {
  return kQuad4.values(xi);
}
Quad4::Gradients Quad4::gradients(const Point& xi) {
  return kQuad4.gradients(xi);
}
Quad4::SecondDerivatives Quad4::secondDerivatives(const Point& xi) {
  return kQuad4.secondDerivatives(xi);
}
Eigen::Matrix<double, 2, 4> Quad4::nodeCoordinates() {
  return kQuad4.nodeCoordinates();
}

Quad9::Values Quad9::values(const Point& xi) {
  return kQuad9.values(xi);
}
Quad9::Gradients Quad9::gradients(const Point& xi) {
  return kQuad9.gradients(xi);
}
Quad9::SecondDerivatives Quad9::secondDerivatives(const Point& xi) {
  return kQuad9.secondDerivatives(xi);
}
Eigen::Matrix<double, 2, 9> Quad9::nodeCoordinates() {
  return kQuad9.nodeCoordinates();
}

Hex8::Values Hex8::values(const Point& xi) {
  return kHex8.values(xi);
}
Hex8::Gradients Hex8::gradients(const Point& xi) {
  return kHex8.gradients(xi);
}
Eigen::Matrix<double, 3, 8> Hex8::nodeCoordinates() {
  return kHex8.nodeCoordinates();
}

Hex27::Values Hex27::values(const Point& xi) {
  return kHex27.values(xi);
}
Hex27::Gradients Hex27::gradients(const Point& xi) {
  return kHex27.gradients(xi);
}
Eigen::Matrix<double, 3, 27> Hex27::nodeCoordinates() {
  return kHex27.nodeCoordinates();
}

Hex18::Values Hex18::values(const Point& xi) {
  return kHex18.values(xi);
}
Hex18::Gradients Hex18::gradients(const Point& xi) {
  return kHex18.gradients(xi);
}
Eigen::Matrix<double, 3, 18> Hex18::nodeCoordinates() {
  return kHex18.nodeCoordinates();
}

}  // namespace cc::shape
