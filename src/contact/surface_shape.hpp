// Shape functions of contact surface segments (Quad4 bilinear, Quad9 biquadratic) with first
// and second derivatives, templated on the scalar type so that the exact contact tangent can
// differentiate through the projection parameter xi (automatic differentiation).
// Node order as in mesh.hpp: corners counter-clockwise, mid-edges 01,12,23,30, centre.
#pragma once

#include <Eigen/Core>
#include <array>

namespace cc::contact {

enum class SegmentType { Quad4, Quad9 };

constexpr int segmentNodes(SegmentType type) {
  return type == SegmentType::Quad4 ? 4 : 9;
}

// Values N_k, first derivatives N_k,i and second derivatives N_k,ij (i,j = xi^1, xi^2) of the
// segment's shape functions at (xi1, xi2). Eq. (1): rho = N_k(xi) x^(k).
template <class Scalar>
struct SurfaceShape {
  static constexpr int kMaxNodes = 9;
  int count = 0;
  std::array<Scalar, kMaxNodes> value{};
  std::array<std::array<Scalar, 2>, kMaxNodes> first{};   // [k][i] = dN_k / dxi^i
  std::array<std::array<Scalar, 3>, kMaxNodes> second{};  // [k][0,1,2] = N_k,11  N_k,12  N_k,22
};

namespace detail {
// 1D Lagrange polynomials on nodes -1, 0, +1 (index 0, 2, 1 in the edge's end-mid-end order is
// avoided: here index 0 = -1, 1 = +1, 2 = 0) with first and second derivatives.
template <class Scalar>
inline void quadratic1d(const Scalar& s, std::array<Scalar, 3>& n, std::array<Scalar, 3>& dn,
                        std::array<Scalar, 3>& ddn) {
  n = {Scalar(0.5) * s * (s - 1.0), Scalar(0.5) * s * (s + 1.0), Scalar(1.0) - s * s};
  dn = {s - 0.5, s + 0.5, Scalar(-2.0) * s};
  ddn = {Scalar(1.0), Scalar(1.0), Scalar(-2.0)};
}
}  // namespace detail

template <class Scalar>
SurfaceShape<Scalar> surfaceShape(SegmentType type, const Scalar& xi1, const Scalar& xi2) {
  SurfaceShape<Scalar> shape;
  if (type == SegmentType::Quad4) {
    static constexpr int kSign[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    shape.count = 4;
    for (int k = 0; k < 4; ++k) {
      const Scalar a = Scalar(1.0) + double(kSign[k][0]) * xi1;
      const Scalar b = Scalar(1.0) + double(kSign[k][1]) * xi2;
      shape.value[k] = 0.25 * a * b;
      shape.first[k] = {Scalar(0.25 * kSign[k][0]) * b, Scalar(0.25 * kSign[k][1]) * a};
      shape.second[k] = {Scalar(0.0), Scalar(0.25 * kSign[k][0] * kSign[k][1]), Scalar(0.0)};
    }
    return shape;
  }
  // Quad9: tensor product of 1D quadratics; index pairs (i along xi1, j along xi2) with
  // 0 = -1, 1 = +1, 2 = 0.
  static constexpr int kIndex[9][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {2, 0},
                                       {1, 2}, {2, 1}, {0, 2}, {2, 2}};
  std::array<Scalar, 3> n1, d1, dd1, n2, d2, dd2;
  detail::quadratic1d(xi1, n1, d1, dd1);
  detail::quadratic1d(xi2, n2, d2, dd2);
  shape.count = 9;
  for (int k = 0; k < 9; ++k) {
    const int i = kIndex[k][0];
    const int j = kIndex[k][1];
    shape.value[k] = n1[i] * n2[j];
    shape.first[k] = {d1[i] * n2[j], n1[i] * d2[j]};
    shape.second[k] = {dd1[i] * n2[j], d1[i] * d2[j], n1[i] * dd2[j]};
  }
  return shape;
}

}  // namespace cc::contact
