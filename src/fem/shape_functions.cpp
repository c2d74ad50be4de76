// The double-precision entry points of the shape-function families (shape_functions.hpp).
#include "fem/shape_functions.hpp"

namespace cc::shape {
namespace {

// Rows: nodes; columns N,11  N,12  N,22 (the order of SurfaceShape::second).
template <int Nodes>
Eigen::Matrix<double, Nodes, 3> secondDerivativesOf(SurfaceType type, const Eigen::Vector2d& xi) {
  const SurfaceShape<double> shape = surfaceShape<double>(type, xi[0], xi[1]);
  Eigen::Matrix<double, Nodes, 3> ddn;
  for (int a = 0; a < Nodes; ++a) {
    for (int c = 0; c < 3; ++c) ddn(a, c) = shape.second[a][c];
  }
  return ddn;
}

}  // namespace

Quad4::Values Quad4::values(const Point& xi) {
  return detail::kQuad4.values(xi);
}
Quad4::Gradients Quad4::gradients(const Point& xi) {
  return detail::kQuad4.gradients(xi);
}
Quad4::SecondDerivatives Quad4::secondDerivatives(const Point& xi) {
  return secondDerivativesOf<4>(SurfaceType::Quad4, xi);
}
Eigen::Matrix<double, 2, 4> Quad4::nodeCoordinates() {
  return detail::kQuad4.nodeCoordinates();
}

Quad9::Values Quad9::values(const Point& xi) {
  return detail::kQuad9.values(xi);
}
Quad9::Gradients Quad9::gradients(const Point& xi) {
  return detail::kQuad9.gradients(xi);
}
Quad9::SecondDerivatives Quad9::secondDerivatives(const Point& xi) {
  return secondDerivativesOf<9>(SurfaceType::Quad9, xi);
}
Eigen::Matrix<double, 2, 9> Quad9::nodeCoordinates() {
  return detail::kQuad9.nodeCoordinates();
}

Hex8::Values Hex8::values(const Point& xi) {
  return detail::kHex8.values(xi);
}
Hex8::Gradients Hex8::gradients(const Point& xi) {
  return detail::kHex8.gradients(xi);
}
Eigen::Matrix<double, 3, 8> Hex8::nodeCoordinates() {
  return detail::kHex8.nodeCoordinates();
}

Hex27::Values Hex27::values(const Point& xi) {
  return detail::kHex27.values(xi);
}
Hex27::Gradients Hex27::gradients(const Point& xi) {
  return detail::kHex27.gradients(xi);
}
Eigen::Matrix<double, 3, 27> Hex27::nodeCoordinates() {
  return detail::kHex27.nodeCoordinates();
}

Hex18::Values Hex18::values(const Point& xi) {
  return detail::kHex18.values(xi);
}
Hex18::Gradients Hex18::gradients(const Point& xi) {
  return detail::kHex18.gradients(xi);
}
Eigen::Matrix<double, 3, 18> Hex18::nodeCoordinates() {
  return detail::kHex18.nodeCoordinates();
}

}  // namespace cc::shape
