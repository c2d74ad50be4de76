// The smoothed (Nagata) geometry of a Quad4 master segment (issue 16, part 2): Nagata's
// quadratic patch (T. Nagata, Simple local interpolation of surfaces using normal vectors, CAGD
// 22 (2005) 327-347) from the segment's corners and nodal normals held fixed over a load step.
// Each edge i -> j becomes the quadratic curve x_i + (d - c) t + c t^2, d = x_j - x_i, whose
// tangents at both ends are orthogonal to the nodal normals there; the patch is the bilinear
// interpolation minus the edge corrections c_e t (1 - t) blended linearly across the segment:
//   rho(xi) = sum_k N_k x_k - sum_e f_e(xi) c_e,   f_e = (1 - s^2)(1 + sigma r) / 8
// (s the coordinate along edge e, r the one across, sigma = +-1 the side of the edge). An edge's
// curve depends on its two nodes and normals only, so neighbouring patches share it (C0), and
// they share the nodal normal at every node, so the surface normal is continuous at the nodes
// and varies continuously along the edges up to O(h^2) (the quadratic edge curve is tangent to
// both neighbours' patches at its ends). With the normals fixed, c_e = C_e d is linear in the
// nodes (C_e a 3x3 matrix of the normals alone): rho is linear in the nodal coordinates, so the
// master-side virtual work and the AD exact tangent stay those of an isoparametric segment with
// 3x3 "shape matrices" N_k I -+ f_e C_e in place of the scalar N_k.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <type_traits>

namespace cc::contact {

// Corners of edge e (0: xi2 = -1, 1: xi1 = +1, 2: xi2 = +1, 3: xi1 = -1), from i to j.
constexpr int nagataEdgeStart(int e) {
  return e;
}
constexpr int nagataEdgeEnd(int e) {
  return (e + 1) % 4;
}

// C_e of Nagata's curvature coefficient c = C_e d for an edge with end normals n0, n1:
// c = (d . dv) / (1 - dc) v + (d . v) / dc dv with v = (n0 + n1)/2, dv = (n0 - n1)/2,
// dc = n0 . dv; the unique c in span(v, dv) with n0 . (d - c) = 0 and n1 . (d + c) = 0 (the
// curve's end tangents d -+ c orthogonal to the normals). Parallel normals (dc -> 0): a straight
// edge, c = 0 (Nagata's rule; the second term would divide the chord's normal component by
// zero, a step between parallel normals that no smooth surface has).
// `tangentialScale` (<= 1) scales the second term, see nagataTangentialScale.
inline Eigen::Matrix3d nagataEdgeMatrix(const Eigen::Vector3d& n0, const Eigen::Vector3d& n1,
                                        double tangentialScale = 1) {
  constexpr double kParallel = 1e-14;
  const Eigen::Vector3d v = 0.5 * (n0 + n1);
  const Eigen::Vector3d dv = 0.5 * (n0 - n1);
  const double dc = n0.dot(dv);
  if (dc < kParallel) return Eigen::Matrix3d::Zero();
  return v * dv.transpose() / (1 - dc) + tangentialScale * dv * v.transpose() / dc;
}

// The second term of c has the length |d . v| / |dv| (dc = |dv|^2), i.e. |d| times the edge's
// asymmetry |d . v| / (|d| |dv|): zero on a circular arc, small where the nodal normals are
// accurate, but of order one where one of them is not (at a free edge of the master, whose
// boundary nodes see the adjacent segments on one side only). Then c ~ d, an end tangent d -+ c
// vanishes and the patch folds (on the meshed trough of smooth_master.md a fold turned the
// normal over: gaps of -0.1 and a singular tangent). The scale caps the term at
// kMaxAsymmetry |d|, which leaves Nagata's interpolation untouched wherever the normals are
// consistent with the chord.
//
// On a master that deforms within the step the term must be held fixed with the normals as a
// vector (nagataFixedTangentialTerm), not as this scale: as a matrix, (d . v)/dc dv has the
// gain 1/|dv| on the chord's normal component, unbounded where the nodal normals are nearly
// parallel (the straight generators of a cylindrical die, whose normals differ by the die's
// elastic rotation, 1e-7). There a rotation of the chord by 1e-6 within the step (the die's
// deformation in the first Newton update) turned a term capped at 0.125 at the step's start
// into one of length 3.5 on an edge of 0.5: the patch folded and the closest-point projection
// on it cycled (ironing, issue 14; NagataPatch.ProjectionOnIroningDieSegmentAfterElasticRotation).
inline double nagataTangentialScale(const Eigen::Vector3d& n0, const Eigen::Vector3d& n1,
                                    const Eigen::Vector3d& chord) {
  constexpr double kMaxAsymmetry = 0.25;
  const double dvLength = 0.5 * (n0 - n1).norm();
  const double tangential = std::abs(chord.dot(0.5 * (n0 + n1)));
  if (tangential <= kMaxAsymmetry * chord.norm() * dvLength) return 1;
  return kMaxAsymmetry * chord.norm() * dvLength / tangential;
}

// The second term of c, s (d . v)/dc dv with the cap s of nagataTangentialScale, for the chord
// d = x_j - x_i of the configuration the normals are taken from (the step's start). Held fixed
// over the step like the normals: c = C_e d + this term, with C_e the first term alone
// (tangentialScale 0), so c stays affine in the nodes (their shape matrices are those of the
// first term) and bounded by kMaxAsymmetry |d| however the nodes move within the step.
// Its direction is that of dv = (n0 - n1)/2, which carries no information where the normals
// differ by less than kDirectionless (radians, half the angle between them): on the straight
// generators of the ironing die they differ by the die's elastic deformation (1e-7), and a
// term there, however capped, bent the edge sideways in a direction that changed from step to
// step (slab elements inverted at the start of a press step). Such an edge stays straight, as
// Nagata's rule makes exactly parallel ones.
inline Eigen::Vector3d nagataFixedTangentialTerm(const Eigen::Vector3d& n0,
                                                 const Eigen::Vector3d& n1,
                                                 const Eigen::Vector3d& chord) {
  constexpr double kDirectionless = 1e-3;
  const Eigen::Vector3d v = 0.5 * (n0 + n1);
  const Eigen::Vector3d dv = 0.5 * (n0 - n1);
  const double dc = n0.dot(dv);
  if (dv.norm() < kDirectionless) return Eigen::Vector3d::Zero();
  return nagataTangentialScale(n0, n1, chord) * chord.dot(v) / dc * dv;
}

// Nodal normals of a Quad4 master segment, in its node order (unit vectors, outward on the
// master, i.e. pointing to the slave side), and the tangential scale of each edge.
struct NodalNormals {
  // Zero until set (a faceted master never sets them; copying points copies them).
  std::array<Eigen::Vector3d, 4> normal{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                        Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<double, 4> tangentialScale{1, 1, 1, 1};
  // Per edge, a correction added to C_e d (nagataFixedTangentialTerm; zero: c = C_e d).
  std::array<Eigen::Vector3d, 4> fixedCorrection{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                                 Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  // Per edge, a crease of the master (MasterSurface::updateNormals): the edge stays straight
  // (c = 0), the same from both sides, whose corner normals there differ.
  std::array<bool, 4> straight{false, false, false, false};
  Eigen::Vector3d& operator[](int k) { return normal[k]; }
  const Eigen::Vector3d& operator[](int k) const { return normal[k]; }
  auto begin() { return normal.begin(); }
  auto end() { return normal.end(); }
  Eigen::Matrix3d edgeMatrix(int e) const {
    if (straight[e]) return Eigen::Matrix3d::Zero();
    return nagataEdgeMatrix(normal[nagataEdgeStart(e)], normal[nagataEdgeEnd(e)],
                            tangentialScale[e]);
  }
};

// f_e and its first and second parametric derivatives at xi (second: 11, 12, 22).
template <class Scalar>
struct NagataBlend {
  std::array<Scalar, 4> value;
  std::array<std::array<Scalar, 2>, 4> first;
  std::array<std::array<Scalar, 3>, 4> second;
};

template <class Scalar>
NagataBlend<Scalar> nagataBlend(const Scalar& xi1, const Scalar& xi2) {
  NagataBlend<Scalar> b;
  for (int e = 0; e < 4; ++e) {
    const int along = e % 2 == 0 ? 0 : 1;  // edges 0, 2 run along xi1; 1, 3 along xi2
    const double sigma = e == 0 || e == 3 ? -1.0 : 1.0;
    const Scalar& s = along == 0 ? xi1 : xi2;
    const Scalar& r = along == 0 ? xi2 : xi1;
    const Scalar bubble = (1.0 - s * s) / 8.0;
    const Scalar side = 1.0 + sigma * r;
    b.value[e] = bubble * side;
    const Scalar ds = -s * side / 4.0, dr = sigma * bubble;
    const Scalar dss = -side / 4.0, dsr = -sigma * s / 4.0;
    b.first[e][along] = ds;
    b.first[e][1 - along] = dr;
    b.second[e][along == 0 ? 0 : 2] = dss;
    b.second[e][1] = dsr;
    b.second[e][along == 0 ? 2 : 0] = Scalar(0.0);
  }
  return b;
}

// C^T u for a double matrix C and a vector of any scalar (Eigen does not mix double and AD).
template <class Scalar>
Eigen::Matrix<Scalar, 3, 1> transposeTimes(const Eigen::Matrix3d& C,
                                           const Eigen::Matrix<Scalar, 3, 1>& u) {
  Eigen::Matrix<Scalar, 3, 1> v;
  for (int a = 0; a < 3; ++a) v[a] = C(0, a) * u[0] + C(1, a) * u[1] + C(2, a) * u[2];
  return v;
}

// The edge corrections c_e = C_e (x_j - x_i) + fixedCorrection_e of a segment with corners
// `nodes` (3 x 4).
template <class Scalar>
std::array<Eigen::Matrix<Scalar, 3, 1>, 4> nagataCorrections(
    const Eigen::Matrix<Scalar, 3, Eigen::Dynamic>& nodes, const NodalNormals& normals) {
  std::array<Eigen::Matrix<Scalar, 3, 1>, 4> c;
  for (int e = 0; e < 4; ++e) {
    const int i = nagataEdgeStart(e), j = nagataEdgeEnd(e);
    const Eigen::Matrix<Scalar, 3, 1> chord = nodes.col(j) - nodes.col(i);
    c[e] = transposeTimes<Scalar>(normals.edgeMatrix(e).transpose(), chord);
    for (int a = 0; a < 3; ++a) c[e][a] += normals.fixedCorrection[e][a];
  }
  return c;
}

// Adds the Nagata terms -sum_e f_e c_e to rho, rho_i and (if given) rho_ij of the bilinear
// segment.
template <class Scalar>
void addNagataCorrection(
    const Eigen::Matrix<Scalar, 3, Eigen::Dynamic>& nodes, const NodalNormals& normals,
    const Scalar& xi1, const Scalar& xi2, Eigen::Matrix<Scalar, 3, 1>& rho,
    std::array<Eigen::Matrix<Scalar, 3, 1>, 2>& rhoCov,
    std::type_identity_t<std::array<Eigen::Matrix<Scalar, 3, 1>, 3>>* rhoSecond) {
  const NagataBlend<Scalar> b = nagataBlend(xi1, xi2);
  const std::array<Eigen::Matrix<Scalar, 3, 1>, 4> c = nagataCorrections(nodes, normals);
  for (int e = 0; e < 4; ++e) {
    rho -= b.value[e] * c[e];
    for (int i = 0; i < 2; ++i) rhoCov[i] -= b.first[e][i] * c[e];
    if (rhoSecond) {
      for (int s = 0; s < 3; ++s) (*rhoSecond)[s] -= b.second[e][s] * c[e];
    }
  }
}

// (d rho / d x_k)^T u for master corner k, the rows of the "shape matrix" of the smoothed
// segment: N_k u + sum over edges e starting at k of f_e C_e^T u - over edges ending at k.
// `weights` are f_e (for rho) or f_e,j (for rho_,j), `shapeValue` N_k or N_k,j.
template <class Scalar>
Eigen::Matrix<Scalar, 3, 1> nagataShapeTranspose(int k, const Scalar& shapeValue,
                                                 const std::array<Scalar, 4>& weights,
                                                 const NodalNormals& normals,
                                                 const Eigen::Matrix<Scalar, 3, 1>& u) {
  Eigen::Matrix<Scalar, 3, 1> v = shapeValue * u;
  for (int e = 0; e < 4; ++e) {
    const int i = nagataEdgeStart(e), j = nagataEdgeEnd(e);
    if (k != i && k != j) continue;
    const Eigen::Matrix<Scalar, 3, 1> Ctu = transposeTimes(normals.edgeMatrix(e), u);
    v += (k == i ? 1.0 : -1.0) * weights[e] * Ctu;
  }
  return v;
}

}  // namespace cc::contact
