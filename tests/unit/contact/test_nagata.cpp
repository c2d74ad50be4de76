// The smoothed master geometry (Nagata patches, contact/nagata.hpp; issue 16 part 2) against
// analytic surfaces and finite differences: a flat patch stays flat, the patch over exact
// nodal normals reproduces a cylinder's and a sphere's normal to O(h^2) or better, neighbouring
// patches share their edges (C0) and the nodal normal at their corners, the derivatives that
// feed the covariant frame are those of rho, and the master's nodal normals are exact on a
// uniform mesh of a cylinder.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include "contact/geometry.hpp"
#include "contact/master_surface.hpp"
#include "contact/projection.hpp"

namespace cc::contact {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// A surface given by its point and unit normal as functions of two parameters (u, v).
struct AnalyticSurface {
  std::function<Vector3d(double, double)> point;
  std::function<Vector3d(double, double)> normal;
};

// Cylinder of radius R about the y axis, outward normal: u is the angle, v the axial position.
AnalyticSurface cylinder(double R) {
  return {[R](double u, double v) { return Vector3d(R * std::sin(u), v, -R * std::cos(u)); },
          [](double u, double) { return Vector3d(std::sin(u), 0, -std::cos(u)); }};
}

// Sphere of radius R about the origin, outward normal: u, v spherical angles around -z.
AnalyticSurface sphere(double R) {
  auto n = [](double u, double v) {
    return Vector3d(std::sin(u) * std::cos(v), std::sin(v), -std::cos(u) * std::cos(v));
  };
  return {[R, n](double u, double v) { return Vector3d(R * n(u, v)); }, n};
}

// A Quad4 segment with corners at parameters (u0 -+ h/2, v0 -+ h/2), counter-clockwise seen
// from the outward normal's side, and its exact nodal normals.
struct Patch {
  NodeMatrix<double> nodes{3, 4};
  NodalNormals normals;
};

Patch patchOn(const AnalyticSurface& s, double u0, double v0, double h) {
  // Order chosen so that rho_1 x rho_2 points along the outward normal.
  const double du[4] = {-1, 1, 1, -1}, dv[4] = {-1, -1, 1, 1};
  Patch p;
  for (int k = 0; k < 4; ++k) {
    const double u = u0 + 0.5 * h * du[k], v = v0 - 0.5 * h * dv[k];
    p.nodes.col(k) = s.point(u, v);
    p.normals[k] = s.normal(u, v);
  }
  return p;
}

// Largest angle between the patch normal and the surface normal at the patch points' closest
// points, and largest distance of the patch points from the surface, over a grid of xi.
struct PatchError {
  double normal = 0;
  double position = 0;
};

PatchError patchError(const Patch& p, const std::function<double(const Vector3d&)>& distance,
                      const std::function<Vector3d(const Vector3d&)>& exactNormal, bool smooth) {
  PatchError e;
  for (double a = -1; a <= 1.0001; a += 0.25) {
    for (double b = -1; b <= 1.0001; b += 0.25) {
      const SurfaceFrame<double> f = surfaceFrame<double>(shape::SurfaceType::Quad4, p.nodes, a, b,
                                                          smooth ? &p.normals : nullptr);
      const Vector3d n = exactNormal(f.rho);
      e.normal = std::max(e.normal, std::atan2(f.normal.cross(n).norm(), f.normal.dot(n)));
      e.position = std::max(e.position, std::abs(distance(f.rho)));
    }
  }
  return e;
}

// Errors at h and h/2 on a cylinder (R = 1) and a sphere (R = 1).
std::array<PatchError, 2> cylinderErrors(bool smooth) {
  std::array<PatchError, 2> errors;
  const double hs[2] = {0.2, 0.1};
  for (int k = 0; k < 2; ++k) {
    const Patch p = patchOn(cylinder(1), 0.3, 0.1, hs[k]);
    errors[k] = patchError(
        p, [](const Vector3d& x) { return std::hypot(x.x(), x.z()) - 1; },
        [](const Vector3d& x) { return Vector3d(x.x(), 0, x.z()).normalized(); }, smooth);
  }
  return errors;
}

std::array<PatchError, 2> sphereErrors(bool smooth) {
  std::array<PatchError, 2> errors;
  const double hs[2] = {0.2, 0.1};
  for (int k = 0; k < 2; ++k) {
    const Patch p = patchOn(sphere(1), 0.3, 0.2, hs[k]);
    errors[k] = patchError(
        p, [](const Vector3d& x) { return x.norm() - 1; },
        [](const Vector3d& x) { return x.normalized(); }, smooth);
  }
  return errors;
}

TEST(NagataPatch, ReproducesCylinderNormalToSecondOrder) {
  const auto smooth = cylinderErrors(true);
  const auto faceted = cylinderErrors(false);
  const double order = std::log2(smooth[0].normal / smooth[1].normal);
  EXPECT_GT(order, 1.9) << smooth[0].normal << " " << smooth[1].normal;
  // The faceted segment's normal is off by half the segment's angle (first order).
  EXPECT_NEAR(faceted[1].normal, 0.05, 0.005);
  EXPECT_LT(smooth[1].normal, 0.02 * faceted[1].normal);
  // Position: third order or better (the faceted chord: second order, sagitta h^2 / 8).
  EXPECT_GT(std::log2(smooth[0].position / smooth[1].position), 2.9);
  EXPECT_LT(smooth[1].position, 0.05 * faceted[1].position);
}

TEST(NagataPatch, ReproducesSphereNormalToSecondOrder) {
  const auto smooth = sphereErrors(true);
  const auto faceted = sphereErrors(false);
  const double order = std::log2(smooth[0].normal / smooth[1].normal);
  EXPECT_GT(order, 1.9) << smooth[0].normal << " " << smooth[1].normal;
  EXPECT_LT(smooth[1].normal, 0.05 * faceted[1].normal);
  EXPECT_GT(std::log2(smooth[0].position / smooth[1].position), 2.9);
}

TEST(NagataPatch, FlatPatchStaysFlat) {
  Patch p;
  p.nodes << -1.0, 1.1, 0.9, -1.2,  //
      -1.0, -0.9, 1.1, 0.8,         //
      0, 0, 0, 0;
  // Rotate the plane out of z = 0 so that no component is trivially zero.
  const Eigen::Matrix3d rotation =
      (Eigen::AngleAxisd(0.4, Vector3d::UnitX()) * Eigen::AngleAxisd(-0.7, Vector3d::UnitY()))
          .toRotationMatrix();
  p.nodes = rotation * p.nodes;
  for (Vector3d& n : p.normals) n = rotation * Vector3d::UnitZ();
  for (double a : {-1.0, -0.3, 0.6}) {
    for (double b : {-0.8, 0.1, 1.0}) {
      const SurfaceFrame<double> s =
          surfaceFrame<double>(shape::SurfaceType::Quad4, p.nodes, a, b, &p.normals);
      const SurfaceFrame<double> f = surfaceFrame<double>(shape::SurfaceType::Quad4, p.nodes, a, b);
      EXPECT_LT((s.rho - f.rho).norm(), 1e-15);
      EXPECT_LT(s.curvature.norm(), 1e-15);
      EXPECT_LT((s.normal - rotation * Vector3d::UnitZ()).norm(), 1e-15);
    }
  }
}

// Largest angle between the two neighbours' normals along their shared edge, and the largest
// distance between their edge points.
std::array<double, 2> edgeMismatch(const Patch& left, const Patch& right, bool smooth) {
  std::array<double, 2> mismatch{0, 0};
  for (double t = -1; t <= 1.0001; t += 0.05) {
    const auto l = surfaceFrame<double>(shape::SurfaceType::Quad4, left.nodes, 1.0, t,
                                        smooth ? &left.normals : nullptr);
    const auto r = surfaceFrame<double>(shape::SurfaceType::Quad4, right.nodes, -1.0, t,
                                        smooth ? &right.normals : nullptr);
    mismatch[0] = std::max(mismatch[0], std::acos(std::min(1.0, l.normal.dot(r.normal))));
    mismatch[1] = std::max(mismatch[1], (l.rho - r.rho).norm());
  }
  return mismatch;
}

// Two segments of a sphere sharing the edge 1-2 of the first (= edge 3-0 of the second, run the
// other way): the same curve from both sides (C0), and at every corner the patch normal is the
// nodal normal, so the normal is continuous at the nodes. Between the nodes Nagata's patches
// are not exactly C1: the normals of the two sides differ along the edge, but by O(h^2), against
// the faceted segments' kink of O(h) (the angle between their planes).
TEST(NagataPatch, NeighboursShareEdgeAndCornerNormals) {
  std::array<std::array<double, 2>, 2> smooth, faceted;
  const double hs[2] = {0.4, 0.2};
  for (int k = 0; k < 2; ++k) {
    const double h = hs[k];
    const Patch left = patchOn(sphere(1), 0.3, 0.2, h);
    const Patch right = patchOn(sphere(1), 0.3 + h, 0.2, h);
    ASSERT_LT((left.nodes.col(1) - right.nodes.col(0)).norm(), 1e-14);
    ASSERT_LT((left.nodes.col(2) - right.nodes.col(3)).norm(), 1e-14);
    smooth[k] = edgeMismatch(left, right, true);
    faceted[k] = edgeMismatch(left, right, false);
    EXPECT_LT(smooth[k][1], 1e-15);
  }
  EXPECT_GT(std::log2(smooth[0][0] / smooth[1][0]), 1.9) << smooth[0][0] << " " << smooth[1][0];
  EXPECT_NEAR(std::log2(faceted[0][0] / faceted[1][0]), 1.0, 0.1);
  EXPECT_LT(smooth[1][0], 0.1 * faceted[1][0]);
  const Patch left = patchOn(sphere(1), 0.3, 0.2, 0.4);
  const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int k = 0; k < 4; ++k) {
    const auto f = surfaceFrame<double>(shape::SurfaceType::Quad4, left.nodes, corner[k][0],
                                        corner[k][1], &left.normals);
    EXPECT_LT((f.normal - left.normals[k]).norm(), 1e-13) << k;
  }
}

// rho_i and rho_ij (which give a_ij, h_ij and the Christoffel symbols) are the derivatives of
// rho: central differences on a warped segment with unrelated normals.
TEST(NagataPatch, DerivativesMatchFiniteDifferences) {
  Patch p;
  p.nodes << -1.1, 0.9, 1.2, -0.8,  //
      -0.9, -1.1, 1.0, 0.8,         //
      0.05, -0.1, 0.12, -0.04;
  p.normals.normal = {Vector3d(0.1, 0.2, 1).normalized(), Vector3d(-0.2, 0.1, 1).normalized(),
                      Vector3d(-0.1, -0.3, 1).normalized(), Vector3d(0.25, -0.1, 1).normalized()};
  p.normals.tangentialScale = {1.0, 0.7, 1.0, 0.4};  // and the limiter's scales
  const Vector2d xi(0.23, -0.61);
  const double h = 1e-5;
  auto rhoAt = [&](const Vector2d& x) {
    Vector3d rho;
    std::array<Vector3d, 2> cov;
    interpolateSegment(shape::SurfaceType::Quad4, p.nodes, &p.normals, x[0], x[1], rho, cov,
                       nullptr);
    return rho;
  };
  auto covAt = [&](const Vector2d& x, int i) {
    return surfaceFrame<double>(shape::SurfaceType::Quad4, p.nodes, x[0], x[1], &p.normals)
        .rhoCov[i];
  };
  const SurfaceFrame<double> f =
      surfaceFrame<double>(shape::SurfaceType::Quad4, p.nodes, xi[0], xi[1], &p.normals);
  for (int i = 0; i < 2; ++i) {
    const Vector2d step = h * Vector2d::Unit(i);
    EXPECT_LT((f.rhoCov[i] - (rhoAt(xi + step) - rhoAt(xi - step)) / (2 * h)).norm(), 1e-9);
    for (int j = 0; j < 2; ++j) {
      const Vector3d fd = (covAt(xi + step, j) - covAt(xi - step, j)) / (2 * h);
      EXPECT_LT((f.second(i, j) - fd).norm(), 1e-8) << i << j;
    }
  }
  // Not bilinear: the patch has curvature where the bilinear segment's h_12 alone would be.
  const SurfaceFrame<double> b =
      surfaceFrame<double>(shape::SurfaceType::Quad4, p.nodes, xi[0], xi[1]);
  EXPECT_GT((f.curvature - b.curvature).norm(), 1e-2);
}

// Nagata's edge curve x0 + (d - c) t + c t^2 has end tangents orthogonal to the end normals.
TEST(NagataPatch, EdgeCurveIsTangentToBothNormals) {
  const Vector3d n0 = Vector3d(0.3, -0.1, 1).normalized(),
                 n1 = Vector3d(-0.2, 0.15, 1).normalized();
  const Vector3d d(1.0, 0.2, 0.05);
  const Vector3d c = nagataEdgeMatrix(n0, n1) * d;
  EXPECT_LT(std::abs(n0.dot(d - c)), 1e-15);
  EXPECT_LT(std::abs(n1.dot(d + c)), 1e-15);
  EXPECT_EQ(nagataEdgeMatrix(n0, n0), Eigen::Matrix3d::Zero());
}

// A free-edge node whose normal is that of its one adjacent segment, exactly orthogonal to the
// chord, and the other end's normal tilted by theta: the unlimited coefficient has c ~ -d (the end
// tangent d + c of length O(theta)), the limited one keeps |c| <= 0.25 |d| + O(theta) |d|.
TEST(NagataPatch, TangentialScaleKeepsOneSidedEdgeFromFolding) {
  const double theta = 0.025;
  const Vector3d d(0.5, 0, 0);
  const Vector3d n0 = Vector3d::UnitZ();
  const Vector3d n1(-std::sin(theta), 0, std::cos(theta));
  const Vector3d unlimited = nagataEdgeMatrix(n0, n1) * d;
  EXPECT_LT(std::min((d - unlimited).norm(), (d + unlimited).norm()), 2 * theta * d.norm());
  const double scale = nagataTangentialScale(n0, n1, d);
  EXPECT_NEAR(scale, 0.25, 0.01);  // asymmetry cos(theta/2) ~ 1 against the cap 1/4
  const Vector3d limited = nagataEdgeMatrix(n0, n1, scale) * d;
  EXPECT_LT(limited.norm(), 0.25 * d.norm() + theta * d.norm());
  EXPECT_GT(std::min((d - limited).norm(), (d + limited).norm()), 0.7 * d.norm());
}

// The projection onto a smoothed segment lands on the patch (orthogonality of r - rho to the
// patch's tangents), and the master surface's nodal normals on a uniform mesh of a cylinder are
// the exact ones.
TEST(NagataPatch, ProjectionAndNodalNormalsOnMeshedCylinder) {
  const int n = 8;        // segments around a quarter, 2 along the axis
  const double h = 0.15;  // angle per segment
  Eigen::Matrix3Xd x(3, 3 * (n + 1));
  for (int a = 0; a <= 2; ++a) {
    for (int i = 0; i <= n; ++i) x.col(a * (n + 1) + i) = cylinder(1).point(i * h - 0.5, 0.2 * a);
  }
  FaceSet faces;
  faces.type = CellType::Quad4;
  faces.connectivity.resize(2 * n, 4);
  for (int a = 0; a < 2; ++a) {
    for (int i = 0; i < n; ++i) {
      const int base = a * (n + 1) + i, up = base + n + 1;
      faces.connectivity.row(a * n + i) << base, base + 1, up + 1, up;
    }
  }
  MasterSurface master(faces);
  master.setSmooth(true);
  master.updateNormals(x);
  // Orientation check: the faces' rho_1 x rho_2 must be the outward normal (else flip order).
  const NodalNormals normals = master.segmentNormals(n + 3);
  for (int k = 0; k < 4; ++k) {
    const Vector3d node = x.col(faces.connectivity(n + 3, k));
    const Vector3d exact = Vector3d(node.x(), 0, node.z()).normalized();
    // Interior nodes along the angle: the average of two symmetric facets is exact.
    EXPECT_LT((normals[k] - (exact.dot(normals[k]) > 0 ? exact : Vector3d(-exact))).norm(), 1e-14);
  }
  const Vector3d point(0.31, 0.15, -1.2);
  master.buildSearchGrid(x, 1.0);
  const SegmentProjection found = master.search(point, x);
  ASSERT_TRUE(found.found());
  const NodalNormals segmentNormals = master.segmentNormals(found.segment);
  const SurfaceFrame<double> f =
      surfaceFrame<double>(shape::SurfaceType::Quad4, master.segmentNodes(found.segment, x),
                           found.xi[0], found.xi[1], &segmentNormals);
  EXPECT_LT(std::abs(f.rhoCov[0].dot(point - f.rho)), 1e-12);
  EXPECT_LT(std::abs(f.rhoCov[1].dot(point - f.rho)), 1e-12);
  // The smoothed surface is within O(h^4) of the cylinder: the distance found is 0.2 up to that.
  EXPECT_NEAR(found.distance, std::hypot(point.x(), point.z()) - 1, 1e-5);
}

// The segment of the ironing die (input/stress/ironing, STS, surface=smooth, issue 14) on which
// the closest-point projection of slave point 140 broke down at the first iterations of step 2:
// nodes and angle-weighted nodal normals at the step's start (the normals of the straight
// generators, edges 0 and 2 along y, differ by the die's elastic rotation, ~1e-7), the nodes
// after the first Newton update (the die moved 0.07 down and rotated its generators by ~1e-6),
// and the slave point, as the run printed them.
struct IroningDieSegment {
  NodeMatrix<double> start{3, 4}, current{3, 4};
  NodalNormals normals;
  Vector3d point{2.3988644193601987, 1.610139582762278, 2.9422543941260719};
  Vector2d facetedXi{-0.5594014820889327, -0.32380818819550972};
  IroningDieSegment() {
    start << 2.2742341292006305, 2.2742341826088452, 2.6343922187153561, 2.6343921960770764,
        1.4999994556432377, 1.9999999999999993, 2.0000000000000009, 1.499997964427668,
        3.0191131690450885, 3.0191131935063393, 2.9523638983020661, 2.9523639566076141;
    current << 2.2741858244846016, 2.2741857046160141, 2.6343708270306325, 2.634371270573634,
        1.5000040538270432, 1.9999999689902499, 2.0000009369192182, 1.4999540366723558,
        2.949119566476889, 2.9491236175289033, 2.8824505226513693, 2.8824500681553511;
    normals[0] = Vector3d(-0.2419187157089408, 1.3046024641976233e-07, -0.97029651910625747);
    normals[1] = Vector3d(-0.24191877534422079, -6.4576438440762932e-16, -0.97029650423772651);
    normals[2] = Vector3d(-0.12186627991026694, -1.0823826837747496e-16, -0.99254652778639674);
    normals[3] = Vector3d(-0.12186641142920634, -1.5852853946395729e-07, -0.992546511638292);
  }
  Vector3d chord(const NodeMatrix<double>& x, int e) const {
    return x.col(nagataEdgeEnd(e)) - x.col(nagataEdgeStart(e));
  }
};

TEST(NagataPatch, ProjectionOnIroningDieSegmentAfterElasticRotation) {
  const IroningDieSegment die;
  // The cause: held as a scale of the linear term, the tangential term of edge 2 (capped at
  // a quarter of the chord at the step's start) grows with the current chord's normal
  // component by the gain 1/|dv| ~ 1e7 to several chord lengths: the patch folds.
  NodalNormals asScale = die.normals;
  for (int e = 0; e < 4; ++e) {
    asScale.tangentialScale[e] = nagataTangentialScale(
        die.normals[nagataEdgeStart(e)], die.normals[nagataEdgeEnd(e)], die.chord(die.start, e));
  }
  const auto scaled = nagataCorrections<double>(die.current, asScale);
  EXPECT_GT(scaled[2].norm(), 4 * die.chord(die.current, 2).norm());
  // The fix: the term held fixed as the vector of the step's start, at most a quarter chord.
  NodalNormals fixed = die.normals;
  for (int e = 0; e < 4; ++e) {
    fixed.tangentialScale[e] = 0;
    fixed.fixedCorrection[e] = nagataFixedTangentialTerm(
        die.normals[nagataEdgeStart(e)], die.normals[nagataEdgeEnd(e)], die.chord(die.start, e));
  }
  const auto corrections = nagataCorrections<double>(die.current, fixed);
  for (int e = 0; e < 4; ++e) {
    EXPECT_LE(corrections[e].norm(), 0.25 * die.chord(die.current, e).norm() + 1e-9) << e;
  }
  const ProjectionResult p = closestPointProjection(shape::SurfaceType::Quad4, die.current,
                                                    die.point, die.facetedXi, {}, &fixed);
  ASSERT_TRUE(p.converged);
  ASSERT_TRUE(p.inside());
  // Orthogonality (eq. (23)): rho_i . (r - rho) = 0, relative to |rho_i| |r - rho|.
  const SurfaceFrame<double> f =
      surfaceFrame<double>(shape::SurfaceType::Quad4, die.current, p.xi[0], p.xi[1], &fixed);
  const double distance = (die.point - f.rho).norm();
  for (int i = 0; i < 2; ++i) {
    EXPECT_LT(std::abs(f.rhoCov[i].dot(die.point - f.rho)), 1e-12 * f.rhoCov[i].norm() * distance);
  }
  // The closest point of the whole patch: no point of a 401 x 401 sampling of [-1, 1]^2 is
  // closer, and the nearest sample lies next to the projection.
  double nearest = std::numeric_limits<double>::infinity();
  Vector2d nearestXi = Vector2d::Zero();
  for (int a = 0; a <= 400; ++a) {
    for (int b = 0; b <= 400; ++b) {
      const Vector2d xi(-1 + a / 200.0, -1 + b / 200.0);
      Vector3d rho;
      std::array<Vector3d, 2> tangents;
      interpolateSegment(shape::SurfaceType::Quad4, die.current, &fixed, xi[0], xi[1], rho,
                         tangents, nullptr);
      if ((die.point - rho).norm() < nearest) nearest = (die.point - rho).norm(), nearestXi = xi;
    }
  }
  EXPECT_GE(nearest, distance - 1e-14);
  EXPECT_LT((nearestXi - p.xi).norm(), 2.0 / 200);
  // And it lies between the facet and the die's cylinder (R = 3, 7 degrees per segment): within
  // the sagitta R (1 - cos 3.5 deg) = 0.0056 of the faceted distance.
  const ProjectionResult flat =
      closestPointProjection(shape::SurfaceType::Quad4, die.current, die.point, die.facetedXi);
  const SurfaceFrame<double> facet =
      surfaceFrame<double>(shape::SurfaceType::Quad4, die.current, flat.xi[0], flat.xi[1]);
  EXPECT_LT(std::abs(distance - (die.point - facet.rho).norm()), 0.0056);
}

// A master surface extruded along y from a profile in the x-z plane (profile nodes i, rows y =
// 0, 0.5, 1): segment (row a, profile i) has the nodes (a, i), (a, i+1), (a+1, i+1), (a+1, i),
// so that a profile running along +x faces +z.
struct ExtrudedMaster {
  Eigen::Matrix3Xd x;
  FaceSet faces;
  int profileNodes = 0;
  explicit ExtrudedMaster(const std::vector<Eigen::Vector2d>& profile) {
    profileNodes = static_cast<int>(profile.size());
    const int m = profileNodes - 1;
    x.resize(3, 3 * profileNodes);
    for (int a = 0; a < 3; ++a) {
      for (int i = 0; i < profileNodes; ++i) {
        x.col(a * profileNodes + i) = Vector3d(profile[i].x(), 0.5 * a, profile[i].y());
      }
    }
    faces.type = CellType::Quad4;
    faces.connectivity.resize(2 * m, 4);
    for (int a = 0; a < 2; ++a) {
      for (int i = 0; i < m; ++i) {
        const int base = a * profileNodes + i, up = base + profileNodes;
        faces.connectivity.row(segment(a, i)) << base, base + 1, up + 1, up;
      }
    }
  }
  int segment(int row, int i) const { return row * (profileNodes - 1) + i; }
};

SurfaceFrame<double> smoothFrame(const MasterSurface& master, const Eigen::Matrix3Xd& x,
                                 int segment, double a, double b) {
  const NodalNormals normals = master.segmentNormals(segment);
  return surfaceFrame<double>(shape::SurfaceType::Quad4, master.segmentNodes(segment, x), a, b,
                              &normals);
}

// A box edge (a flat top z = 0 meeting the flat side x = 0 at 90 degrees): the smoothed surface
// is the box itself, flat on both faces up to the edge, with each face's own normal. Without
// creases (the smoothing before: one averaged normal per node, 45 degrees off both faces at the
// edge) the top bulges by more than 0.05 next to the edge: a sharp tool silently rounded.
TEST(NagataPatch, SmoothingKeepsABoxEdgeSharp) {
  const ExtrudedMaster box({{-2, 0}, {-1, 0}, {0, 0}, {0, -1}, {0, -2}});
  MasterSurface master(box.faces);
  master.setSmooth(true);
  master.updateNormals(box.x);
  for (int a = 0; a < 2; ++a) {
    for (int i = 0; i < 4; ++i) {
      const int s = box.segment(a, i);
      EXPECT_EQ(master.crease(s, 1), i == 1) << s;  // edge 1: xi1 = +1, toward the next node
      EXPECT_EQ(master.crease(s, 3), i == 2) << s;
      EXPECT_FALSE(master.crease(s, 0) || master.crease(s, 2)) << s;
      const bool top = i < 2;
      for (double u : {-1.0, -0.4, 0.3, 0.8, 1.0}) {
        for (double v : {-1.0, 0.2, 1.0}) {
          const SurfaceFrame<double> f = smoothFrame(master, box.x, s, u, v);
          EXPECT_LT(std::abs(top ? f.rho.z() : f.rho.x()), 1e-15) << s << " " << u;
          EXPECT_LT((f.normal - (top ? Vector3d::UnitZ() : Vector3d::UnitX())).norm(), 1e-15);
        }
      }
    }
  }
  master.setCreaseAngle(std::numbers::pi);  // no crease anywhere: the smoothing without them
  master.updateNormals(box.x);
  double bulge = 0;
  for (double u = -1; u <= 1.0001; u += 0.1) {
    bulge = std::max(bulge, std::abs(smoothFrame(master, box.x, box.segment(0, 1), u, 0).rho.z()));
  }
  EXPECT_GT(bulge, 0.05);
}

// Two arcs (facets turning by 10 degrees) meeting at a ridge where the profile turns by 60
// degrees. Away from the ridge the smoothing is as before; at the ridge nodes each side has its
// own normal (the average over its own facets only), the ridge edges stay straight and shared,
// and the curved edges that end on the ridge are still shared by the segments on both sides of
// them (C0: the segments of one side use the same normal at the ridge node).
TEST(NagataPatch, SmoothingKeepsARidgeAndStaysWatertightAroundIt) {
  std::vector<Eigen::Vector2d> profile{{0, 0}};
  double heading = 0.5;  // radians, from +x toward +z; turning clockwise makes the ridge convex
  for (int i = 1; i <= 6; ++i) {
    profile.push_back(profile.back() + 0.5 * Eigen::Vector2d(std::cos(heading), std::sin(heading)));
    heading -= (i == 3 ? 60.0 : 10.0) * std::numbers::pi / 180;
  }
  const ExtrudedMaster ridge(profile);
  MasterSurface master(ridge.faces);
  master.setSmooth(true);
  master.updateNormals(ridge.x);
  for (int a = 0; a < 2; ++a) {
    for (int i = 0; i < 6; ++i) {
      const int s = ridge.segment(a, i);
      EXPECT_EQ(master.crease(s, 1), i == 2) << s;
      EXPECT_EQ(master.crease(s, 3), i == 3) << s;
    }
  }
  // The normal each side has at the ridge: that of its own facet (one facet per side along the
  // profile), 60 degrees apart; the interior nodes keep the average of their two facets.
  const auto facetNormal = [&](int i) {
    const Eigen::Vector2d d = profile[i + 1] - profile[i];
    return Vector3d(-d.y(), 0, d.x()).normalized();
  };
  for (int a = 0; a < 2; ++a) {
    const NodalNormals left = master.segmentNormals(ridge.segment(a, 2));
    const NodalNormals right = master.segmentNormals(ridge.segment(a, 3));
    EXPECT_LT((left[1] - facetNormal(2)).norm(), 1e-14);
    EXPECT_LT((right[0] - facetNormal(3)).norm(), 1e-14);
    EXPECT_LT((left[0] - (facetNormal(1) + facetNormal(2)).normalized()).norm(), 1e-14);
    EXPECT_NEAR(std::acos(left[1].dot(right[0])), 60 * std::numbers::pi / 180, 1e-12);
  }
  double ridgeOffChord = 0, ridgeMismatch = 0, sideMismatch = 0, sideOffChord = 0;
  for (double t = -1; t <= 1.0001; t += 0.1) {
    // The ridge edge (along y), from its two sides: straight, so on the chord x = const.
    const SurfaceFrame<double> l = smoothFrame(master, ridge.x, ridge.segment(0, 2), 1, t);
    const SurfaceFrame<double> r = smoothFrame(master, ridge.x, ridge.segment(0, 3), -1, t);
    ridgeMismatch = std::max(ridgeMismatch, (l.rho - r.rho).norm());
    ridgeOffChord = std::max(ridgeOffChord, (l.rho - ridge.x.col(3)).cwiseAbs()(0) +
                                                (l.rho - ridge.x.col(3)).cwiseAbs()(2));
    // The curved edge (along the profile) from the ridge node, between rows 0 and 1.
    const SurfaceFrame<double> below = smoothFrame(master, ridge.x, ridge.segment(0, 3), t, 1);
    const SurfaceFrame<double> above = smoothFrame(master, ridge.x, ridge.segment(1, 3), t, -1);
    sideMismatch = std::max(sideMismatch, (below.rho - above.rho).norm());
    const Vector3d chordPoint = 0.5 * (1 - t) * ridge.x.col(ridge.profileNodes + 3) +
                                0.5 * (1 + t) * ridge.x.col(ridge.profileNodes + 4);
    sideOffChord = std::max(sideOffChord, (below.rho - chordPoint).norm());
  }
  EXPECT_LT(ridgeMismatch, 1e-15);
  EXPECT_LT(ridgeOffChord, 1e-15);
  EXPECT_LT(sideMismatch, 1e-15);
  EXPECT_GT(sideOffChord, 1e-3);  // that edge is curved: smoothing applies there
}

// Creases are a property of the mesh as given, decided once: a ridge of 25 degrees deformed to
// 35 stays smooth, and one of 35 flattened to 25 stays sharp (a decision on the deformed
// surface would switch the geometry between steps wherever a ridge passes the crease angle).
TEST(NagataPatch, CreasesAreDecidedOnTheMeshAsGiven) {
  const auto profile = [](double ridgeDegrees) {
    const double turn = ridgeDegrees * std::numbers::pi / 180;
    return std::vector<Eigen::Vector2d>{{-1, 0}, {0, 0}, {std::cos(turn), -std::sin(turn)}};
  };
  for (const auto& [given, deformed] : {std::pair{25.0, 35.0}, std::pair{35.0, 25.0}}) {
    const ExtrudedMaster mesh(profile(given));
    MasterSurface master(mesh.faces);
    master.setSmooth(true);
    master.findCreases(mesh.x);
    master.updateNormals(ExtrudedMaster(profile(deformed)).x);
    EXPECT_EQ(master.crease(mesh.segment(0, 0), 1), given > 30) << given;
    EXPECT_EQ(master.creaseCount(), given > 30 ? 2 : 0) << given;
  }
}

// How the facets turn (MasterSurface::facetTurns, the faceted master's start-up hint): on the
// meshed cylinder every edge along the axis turns by the segment angle (0.15) and every edge
// across it by nothing; a flat master has no turning edge; a box edge turns by more than the
// crease angle and is no facet edge of a curved surface.
TEST(NagataPatch, FacetTurnsTellACurvedMeshFromAFlatOneAndAnEdge) {
  std::vector<Eigen::Vector2d> arc, flat, box{{-2, 0}, {-1, 0}, {0, 0}, {0, -1}};
  for (int i = 0; i <= 8; ++i) {
    arc.push_back({std::sin(0.15 * i - 0.5), -std::cos(0.15 * i - 0.5)});
    flat.push_back({0.3 * i, 0});
  }
  const auto turns = [](const std::vector<Eigen::Vector2d>& profile) {
    const ExtrudedMaster mesh(profile);
    return MasterSurface(mesh.faces).facetTurns(mesh.x);
  };
  const MasterSurface::FacetTurns curved = turns(arc);
  EXPECT_EQ(curved.sharedEdges, 7 * 2 + 8);  // 7 along the axis per row, 8 between the rows
  EXPECT_EQ(curved.turning, 7 * 2);
  EXPECT_NEAR(curved.largest, 0.15, 1e-13);
  EXPECT_EQ(turns(flat).turning, 0);
  EXPECT_EQ(turns(box).turning, 0);
  EXPECT_EQ(turns(box).sharedEdges, 2 * 2 + 3);
}

}  // namespace
}  // namespace cc::contact
