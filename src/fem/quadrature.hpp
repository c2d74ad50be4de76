// Gauss-Legendre quadrature on [-1, 1] (1 to 6 points) and its tensor products on the reference
// quadrilateral [-1,1]^2 and hexahedron [-1,1]^3, used by elements and contact surfaces.
#pragma once

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

namespace cc {

// Largest 1D rule provided: 6 points integrate polynomials up to degree 11 exactly.
inline constexpr int kMaxGaussPoints = 6;

struct GaussRule1D {
  std::span<const double> points;   // ascending, symmetric about 0
  std::span<const double> weights;  // positive, summing to 2
};

// The n-point Gauss-Legendre rule, exact for polynomials of degree 2n - 1. The nodes are the
// roots of P_n computed once to machine precision. Throws std::invalid_argument unless
// 1 <= numPoints <= kMaxGaussPoints.
GaussRule1D gaussLegendre(int numPoints);

template <int Dim>
struct QuadraturePoint {
  Eigen::Matrix<double, Dim, 1> xi;  // reference coordinates
  double weight = 0;
};

// n x n (x n) tensor-product rules. Point order: xi runs fastest, then eta, then zeta.
std::vector<QuadraturePoint<2>> gaussQuad(int pointsPerDirection);
std::vector<QuadraturePoint<3>> gaussHex(int pointsPerDirection);

// Fixed-size variant of gaussHex for element kernels (no heap storage, same point order).
template <int N>
std::array<QuadraturePoint<3>, N * N * N> gaussHexFixed() {
  const GaussRule1D rule = gaussLegendre(N);
  std::array<QuadraturePoint<3>, N * N * N> points{};
  int index = 0;
  for (int k = 0; k < N; ++k) {
    for (int j = 0; j < N; ++j) {
      for (int i = 0; i < N; ++i) {
        points[index].xi = Eigen::Vector3d(rule.points[i], rule.points[j], rule.points[k]);
        points[index].weight = rule.weights[i] * rule.weights[j] * rule.weights[k];
        ++index;
      }
    }
  }
  return points;
}

}  // namespace cc
