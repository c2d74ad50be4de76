// Covariant surface geometry at a point of a master segment, section 2.1 of the paper:
// position rho, covariant basis rho_i (2), second derivatives rho_ij (14), unit normal n (3),
// metric a_ij (4) and its inverse a^ij (6), contravariant basis rho^i (7), curvature h_ij (11),
// h^ij (12), mixed h_i^j (13) and the Christoffel symbols Gamma^k_ij (15). Computed once per
// point and iteration, templated on the scalar so the exact tangent can differentiate it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <array>
#include <type_traits>

#include "contact/nagata.hpp"
#include "fem/shape_functions.hpp"

namespace cc::contact {

template <class Scalar>
using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
template <class Scalar>
using Mat2 = Eigen::Matrix<Scalar, 2, 2>;
template <class Scalar>
using NodeMatrix = Eigen::Matrix<Scalar, 3, Eigen::Dynamic>;

// The plain value of a scalar (double, or an automatic-differentiation scalar's value), for
// decisions that must not depend on derivatives.
inline double scalarValue(double x) {
  return x;
}
template <class Scalar>
double scalarValue(const Scalar& x) {
  return x.value();
}

// Index of the symmetric second derivative rho_ij in SurfaceFrame::rhoSecond: 11 -> 0, 12 -> 1,
// 22 -> 2.
constexpr int symmetricIndex(int i, int j) {
  return i + j;
}

template <class Scalar>
struct SurfaceFrame {
  Vec3<Scalar> rho;                         // eq. (1)
  std::array<Vec3<Scalar>, 2> rhoCov;       // rho_i, eq. (2)
  std::array<Vec3<Scalar>, 3> rhoSecond;    // rho_11, rho_12, rho_22
  Vec3<Scalar> normal;                      // n, eq. (3)
  Mat2<Scalar> metric;                      // a_ij, eq. (4)
  Mat2<Scalar> inverseMetric;               // a^ij, eqs. (5)-(6)
  std::array<Vec3<Scalar>, 2> rhoContra;    // rho^i = a^ij rho_j, eq. (7)
  Mat2<Scalar> curvature;                   // h_ij = rho_ij . n, eq. (11)
  Mat2<Scalar> curvatureContra;             // h^ij = h_kn a^ik a^nj, eq. (12)
  Mat2<Scalar> curvatureMixed;              // (i, j) -> h_i^j = h_ik a^kj, eq. (13)
  std::array<Mat2<Scalar>, 2> christoffel;  // christoffel[k](i, j) = Gamma^k_ij, eq. (15)
  Scalar areaElement;                       // sqrt(det a_ij), eq. (10)

  const Vec3<Scalar>& second(int i, int j) const { return rhoSecond[symmetricIndex(i, j)]; }
};

// rho, rho_i and rho_ij of a segment with the given nodes (3 x count) and shape values.
template <class Scalar>
void interpolateSurface(const NodeMatrix<Scalar>& nodes, const shape::SurfaceShape<Scalar>& shape,
                        Vec3<Scalar>& rho, std::array<Vec3<Scalar>, 2>& rhoCov,
                        std::type_identity_t<std::array<Vec3<Scalar>, 3>>* rhoSecond) {
  rho.setZero();
  rhoCov[0].setZero();
  rhoCov[1].setZero();
  if (rhoSecond) {
    for (auto& v : *rhoSecond) v.setZero();
  }
  for (int k = 0; k < shape.count; ++k) {
    const Vec3<Scalar> node = nodes.col(k);
    rho += shape.value[k] * node;
    rhoCov[0] += shape.first[k][0] * node;
    rhoCov[1] += shape.first[k][1] * node;
    if (rhoSecond) {
      for (int s = 0; s < 3; ++s) (*rhoSecond)[s] += shape.second[k][s] * node;
    }
  }
}

template <class Scalar>
Mat2<Scalar> covariantMetric(const std::array<Vec3<Scalar>, 2>& rhoCov) {
  Mat2<Scalar> a;
  a(0, 0) = rhoCov[0].dot(rhoCov[0]);
  a(0, 1) = rhoCov[0].dot(rhoCov[1]);
  a(1, 0) = a(0, 1);
  a(1, 1) = rhoCov[1].dot(rhoCov[1]);
  return a;
}

// Eq. (6): explicit inverse of the 2x2 metric.
template <class Scalar>
Mat2<Scalar> contravariantMetric(const Mat2<Scalar>& metric) {
  const Scalar det = metric(0, 0) * metric(1, 1) - metric(0, 1) * metric(1, 0);
  Mat2<Scalar> inverse;
  inverse(0, 0) = metric(1, 1) / det;
  inverse(1, 1) = metric(0, 0) / det;
  inverse(0, 1) = -metric(0, 1) / det;
  inverse(1, 0) = inverse(0, 1);
  return inverse;
}

template <class Scalar>
Vec3<Scalar> unitNormal(const std::array<Vec3<Scalar>, 2>& rhoCov) {
  const Vec3<Scalar> cross = rhoCov[0].cross(rhoCov[1]);
  return cross / cross.norm();
}

// Eq. (15): Gamma^k_ij = rho_ij . rho^k.
template <class Scalar>
std::array<Mat2<Scalar>, 2> christoffel(const std::array<Vec3<Scalar>, 3>& rhoSecond,
                                        const std::array<Vec3<Scalar>, 2>& rhoContra) {
  std::array<Mat2<Scalar>, 2> gamma;
  for (int k = 0; k < 2; ++k) {
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j)
        gamma[k](i, j) = rhoSecond[symmetricIndex(i, j)].dot(rhoContra[k]);
    }
  }
  return gamma;
}

// Eq. (11): h_ij = rho_ij . n.
template <class Scalar>
Mat2<Scalar> curvature(const std::array<Vec3<Scalar>, 3>& rhoSecond, const Vec3<Scalar>& normal) {
  Mat2<Scalar> h;
  h(0, 0) = rhoSecond[0].dot(normal);
  h(0, 1) = rhoSecond[1].dot(normal);
  h(1, 0) = h(0, 1);
  h(1, 1) = rhoSecond[2].dot(normal);
  return h;
}

// The frame from the surface point and its first and second parametric derivatives (any
// parametrization: a segment's shape functions or an analytic surface).
template <class Scalar>
SurfaceFrame<Scalar> frameFromDerivatives(const Vec3<Scalar>& rho,
                                          const std::array<Vec3<Scalar>, 2>& rhoCov,
                                          const std::array<Vec3<Scalar>, 3>& rhoSecond) {
  SurfaceFrame<Scalar> f;
  f.rho = rho;
  f.rhoCov = rhoCov;
  f.rhoSecond = rhoSecond;
  f.metric = covariantMetric(f.rhoCov);
  f.inverseMetric = contravariantMetric(f.metric);
  f.normal = unitNormal(f.rhoCov);
  for (int i = 0; i < 2; ++i) {
    f.rhoContra[i] = f.inverseMetric(i, 0) * f.rhoCov[0] + f.inverseMetric(i, 1) * f.rhoCov[1];
  }
  f.curvature = curvature(f.rhoSecond, f.normal);
  f.curvatureContra = f.inverseMetric * f.curvature * f.inverseMetric;
  f.curvatureMixed = f.curvature * f.inverseMetric;
  f.christoffel = christoffel(f.rhoSecond, f.rhoContra);
  using std::sqrt;
  f.areaElement = sqrt(f.metric.determinant());
  return f;
}

// rho, rho_i and rho_ij of a master segment at xi: the isoparametric interpolation of eq. (1),
// or with nodal normals (Quad4 only) the smoothed Nagata patch of nagata.hpp, whose metric,
// curvature and Christoffel symbols then follow from eqs. (4)-(15) unchanged.
template <class Scalar>
void interpolateSegment(shape::SurfaceType type, const NodeMatrix<Scalar>& nodes,
                        const NodalNormals* normals, const Scalar& xi1, const Scalar& xi2,
                        Vec3<Scalar>& rho, std::array<Vec3<Scalar>, 2>& rhoCov,
                        std::type_identity_t<std::array<Vec3<Scalar>, 3>>* rhoSecond) {
  const shape::SurfaceShape<Scalar> shape = shape::surfaceShape(type, xi1, xi2);
  interpolateSurface(nodes, shape, rho, rhoCov, rhoSecond);
  if (normals) addNagataCorrection(nodes, *normals, xi1, xi2, rho, rhoCov, rhoSecond);
}

// The complete frame at parameter xi of a segment (smoothed when `normals` is given).
template <class Scalar>
SurfaceFrame<Scalar> surfaceFrame(shape::SurfaceType type, const NodeMatrix<Scalar>& nodes,
                                  const Scalar& xi1, const Scalar& xi2,
                                  const NodalNormals* normals = nullptr) {
  Vec3<Scalar> rho;
  std::array<Vec3<Scalar>, 2> rhoCov;
  std::array<Vec3<Scalar>, 3> rhoSecond;
  interpolateSegment(type, nodes, normals, xi1, xi2, rho, rhoCov, &rhoSecond);
  return frameFromDerivatives(rho, rhoCov, rhoSecond);
}

}  // namespace cc::contact
