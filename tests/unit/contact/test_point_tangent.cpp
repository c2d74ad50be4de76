// Contact point tangents against central finite differences of the contact residual, for each
// kind (NTS, STS, STAS), in stick and slide, on flat and curved masters (issue 4), and on the
// smoothed (Nagata) linear master of issue 16 part 2, with its nodal normals held fixed.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <tuple>
#include <unsupported/Eigen/AutoDiff>

#include "contact/point_evaluation.hpp"
#include "contact/segmentation.hpp"
#include "contact/tangent_parts.hpp"

namespace cc::contact {
namespace {

using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kPenaltyNormal = 2.0e3;
constexpr double kPenaltyTangential = 1.5e3;

// Master segments: a flat distorted Quad4 (h_ij = 0) and a doubly curved Quad9, both with the
// normal pointing to +z (the slave side).
NodeMatrix<double> flatQuad4() {
  NodeMatrix<double> nodes(3, 4);
  nodes << -1.0, 1.1, 0.9, -1.2,  //
      -1.0, -0.9, 1.1, 0.8,       //
      0, 0, 0, 0;
  return nodes;
}

NodeMatrix<double> curvedQuad9() {
  NodeMatrix<double> nodes(3, 9);
  const double corner[9][2] = {{-1, -1}, {1, -1}, {1, 1},  {-1, 1}, {0, -1},
                               {1, 0},   {0, 1},  {-1, 0}, {0, 0}};
  for (int k = 0; k < 9; ++k) {
    const double x = 1.2 * corner[k][0] + 0.1 * corner[k][1];
    const double y = 0.9 * corner[k][1];
    nodes.col(k) << x, y, -0.12 * x * x - 0.08 * y * y + 0.03 * x * y;
  }
  return nodes;
}

// A linear (Quad4) master segment on the curved surface of curvedQuad9, smoothed by Nagata
// patches over the surface's exact normals at its corners (issue 16, part 2): the curvature
// parts of the tangent act on a linear mesh.
NodeMatrix<double> curvedQuad4() {
  return curvedQuad9().leftCols(4);
}

NodalNormals curvedSurfaceNormals() {
  NodalNormals normals;
  const NodeMatrix<double> nodes = curvedQuad4();
  for (int k = 0; k < 4; ++k) {
    const double x = nodes(0, k), y = nodes(1, k);
    // z = -0.12 x^2 - 0.08 y^2 + 0.03 x y: n ~ (-z_x, -z_y, 1).
    normals[k] = Vector3d(0.24 * x - 0.03 * y, 0.16 * y - 0.03 * x, 1).normalized();
  }
  return normals;
}

const NodalNormals kSmoothNormals = curvedSurfaceNormals();

// A slave Quad4 segment facing the master (normal -z), slightly penetrating it.
NodeMatrix<double> slaveQuad4(double depth) {
  NodeMatrix<double> nodes(3, 4);
  nodes << -0.5, -0.6, 0.45, 0.55,  //
      -0.4, 0.5, 0.55, -0.45,       //
      -depth, -depth + 0.002, -depth - 0.001, -depth + 0.001;
  return nodes;
}

struct PointCase {
  PointSetup setup;
  NodeMatrix<double> nodes;
};

// Master nodes are placed first in the item, then the slave nodes.
PointLayout makeLayout(shape::SurfaceType masterType, int slaveCount) {
  PointLayout layout;
  layout.masterType = masterType;
  layout.masterCount = shape::surfaceNodes(masterType);
  for (int k = 0; k < layout.masterCount; ++k) layout.masterLocal[k] = k;
  layout.slaveCount = slaveCount;
  for (int a = 0; a < slaveCount; ++a) layout.slaveLocal[a] = layout.masterCount + a;
  layout.nodeCount = layout.masterCount + slaveCount;
  return layout;
}

// History of a point that was at `previousXi` with traction `traction` (a tangent vector).
PointHistory historyWith(const Vector2d& previousXi, const Vector3d& traction) {
  PointHistory h;
  h.projected = true;
  h.xi = previousXi;
  h.traction = traction;
  h.state = ContactState::Stick;
  return h;
}

LawParameters law(double friction) {
  return {kPenaltyNormal, kPenaltyTangential, friction};
}

// NTS: one slave node at `slavePoint` against `master`; slip `slipScale` times a fixed
// direction in the parameter plane; previous traction of magnitude `traction`.
// `normals`: a smoothed (Nagata) Quad4 master over these nodal normals.
PointCase nodeToSegment(const NodeMatrix<double>& master, shape::SurfaceType type,
                        const Vector3d& slavePoint, double friction, double slipScale,
                        double traction, const NodalNormals* normals = nullptr) {
  PointCase c;
  c.setup.kind = PointKind::NodeToSegment;
  c.setup.layout = makeLayout(type, 1);
  if (normals) {
    c.setup.layout.smoothMaster = true;
    c.setup.layout.masterNormals = *normals;
  }
  c.setup.layout.slaveShape[0] = 1.0;
  c.setup.slave.nodalArea = 0.7;
  c.setup.law = law(friction);
  c.nodes.resize(3, c.setup.layout.nodeCount);
  c.nodes.leftCols(c.setup.layout.masterCount) = master;
  c.nodes.col(c.setup.layout.masterCount) = slavePoint;
  const ProjectionResult p =
      closestPointProjection(type, master, slavePoint, Vector2d::Zero(), {}, normals);
  const SurfaceFrame<double> f = surfaceFrame<double>(type, master, p.xi[0], p.xi[1], normals);
  const Vector3d tangentTraction = traction * (f.rhoCov[0] - 0.4 * f.rhoCov[1]).normalized();
  c.setup.history = historyWith(p.xi - slipScale * Vector2d(0.7, 0.3), tangentTraction);
  c.setup.parameter = p.xi;
  return c;
}

// STS: the point `gauss` with parametric weight `weight` of a slave Quad4 against `master`.
PointCase segmentToSegment(const NodeMatrix<double>& master, shape::SurfaceType type,
                           double friction, double slipScale, double traction, bool freezeArea,
                           double depth = 0.003, const NodalNormals* normals = nullptr,
                           const Vector2d& gauss = Vector2d(0.31, -0.57), double weight = 1.0) {
  PointCase c;
  c.setup.kind = PointKind::SegmentToSegment;
  c.setup.layout = makeLayout(type, 4);
  if (normals) {
    c.setup.layout.smoothMaster = true;
    c.setup.layout.masterNormals = *normals;
  }
  const shape::SurfaceShape<double> shape =
      shape::surfaceShape(shape::SurfaceType::Quad4, gauss[0], gauss[1]);
  for (int a = 0; a < 4; ++a) c.setup.layout.slaveShape[a] = shape.value[a];
  c.setup.slave.segmentType = shape::SurfaceType::Quad4;
  c.setup.slave.gaussPoint = gauss;
  c.setup.slave.gaussWeight = weight;
  c.setup.law = law(friction);
  c.nodes.resize(3, c.setup.layout.nodeCount);
  c.nodes.leftCols(c.setup.layout.masterCount) = master;
  const NodeMatrix<double> slave = slaveQuad4(depth);
  c.nodes.rightCols(4) = slave;
  if (freezeArea) {
    Vector3d point;
    std::array<Vector3d, 2> tangents;
    interpolateSurface(slave, shape, point, tangents, nullptr);
    c.setup.slave.frozenAreaElement = tangents[0].cross(tangents[1]).norm();
  }
  const Vector3d slavePoint = slave * Eigen::Map<const Eigen::Vector4d>(shape.value.data());
  const ProjectionResult p =
      closestPointProjection(type, master, slavePoint, Vector2d::Zero(), {}, normals);
  const SurfaceFrame<double> f = surfaceFrame<double>(type, master, p.xi[0], p.xi[1], normals);
  const Vector3d tangentTraction = traction * (f.rhoCov[1] + 0.2 * f.rhoCov[0]).normalized();
  c.setup.history = historyWith(p.xi + slipScale * Vector2d(0.5, -0.6), tangentTraction);
  c.setup.parameter = p.xi;
  return c;
}

// STAS: a Gauss point of a deformable Quad4 segment (normal -z, facing down) above a rigid
// surface, penetrating it.
PointCase analyticalSurface(const RigidSurface& surface, double friction, double slipScale,
                            double traction) {
  PointCase c;
  c.setup.kind = PointKind::SegmentToAnalytical;
  c.setup.layout = makeLayout(shape::SurfaceType::Quad4, 0);
  c.setup.law = law(friction);
  c.setup.surface = &surface;
  c.setup.parameter = Vector2d(-0.34, 0.52);
  c.setup.gaussWeight = 1.0;
  c.nodes = slaveQuad4(0.004);  // reused as the master: its normal points to -z
  const SurfaceFrame<double> f = surfaceFrame<double>(shape::SurfaceType::Quad4, c.nodes,
                                                      c.setup.parameter[0], c.setup.parameter[1]);
  c.setup.history.projected = true;
  c.setup.history.masterPoint = f.rho - slipScale * (f.rhoCov[0] + 0.5 * f.rhoCov[1]);
  c.setup.history.traction = traction * (f.rhoCov[0] - f.rhoCov[1]).normalized();
  return c;
}

// A rigid plane under the STAS master segment, tilted by `tilt` radians against the segment.
RigidSurface plane(double tilt = 0.05) {
  RigidSurface s;
  s.shape = RigidSurface::Shape::Plane;
  s.origin = Vector3d(0, 0, -0.001);
  s.normal = Vector3d(0, std::sin(tilt), std::cos(tilt));
  return s;
}

RigidSurface parabolicCylinder() {
  RigidSurface s;
  s.shape = RigidSurface::Shape::ParabolicCylinder;
  s.origin = Vector3d(0.1, 0, -0.002);
  s.normal = Vector3d(0, 0, 1);
  s.axis = Vector3d(0, 1, 0);
  s.curvature = 0.05;
  return s;
}

// Central differences of the point force; the step is chosen for an O(h^2) truncation error
// near 1e-10 relative with round-off eps * |f| / h also near 1e-10 for forces of order 1.
MatrixXd finiteDifferenceTangent(const PointCase& c, double h = 1e-6) {
  const int dofs = 3 * c.setup.layout.nodeCount;
  MatrixXd K(dofs, dofs);
  for (int dof = 0; dof < dofs; ++dof) {
    NodeMatrix<double> plus = c.nodes, minus = c.nodes;
    plus(dof % 3, dof / 3) += h;
    minus(dof % 3, dof / 3) -= h;
    K.col(dof) =
        (evaluatePoint(c.setup, plus).force - evaluatePoint(c.setup, minus).force) / (2 * h);
  }
  return K;
}

MatrixXd tangent(const PointCase& c, TangentMode mode, const TangentParts& parts) {
  const PointEvaluation e = evaluatePoint(c.setup, c.nodes);
  EXPECT_TRUE(e.valid);
  MatrixXd K;
  pointTangent(c.setup, c.nodes, e, mode, parts, K);
  return K;
}

double relativeError(const MatrixXd& K, const MatrixXd& reference) {
  return (K - reference).norm() / reference.norm();
}

ContactState stateOf(const PointCase& c) {
  return evaluatePoint(c.setup, c.nodes).response.state;
}

const Vector3d kSlaveBelowFlat(0.21, -0.33, -0.002);
const Vector3d kSlaveBelowCurved(0.27, 0.18, -0.025);

// ---- the normal part (83)-(83b) is the exact linearization (frictionless, ds constant) up to
// the O(g^2) terms the paper neglects (from delta xi's dependence on g, eq. (41) vs (42)) -----

// Relative error of the paper's normal tangent against finite differences at penetration
// depths d, d/2, d/4: it must fall like d^2 and be below 1e-6 at the smallest.
template <class MakeCase>
void expectNormalTangentExactUpToSecondOrder(MakeCase makeCase, double depth) {
  double errors[3];
  for (int k = 0; k < 3; ++k) {
    const PointCase c = makeCase(depth / std::pow(2.0, k));
    ASSERT_EQ(stateOf(c), ContactState::Stick);
    errors[k] = relativeError(tangent(c, TangentMode::Paper, {}), finiteDifferenceTangent(c));
  }
  const double order = std::log2(errors[1] / errors[2]);
  EXPECT_GT(order, 1.8) << errors[0] << " " << errors[1] << " " << errors[2];
  EXPECT_LT(order, 2.2) << errors[0] << " " << errors[1] << " " << errors[2];
  EXPECT_LT(errors[2], 1e-6);
}

TEST(NormalTangent, NodeToSegmentFlatIsExactToSecondOrderInGap) {
  expectNormalTangentExactUpToSecondOrder(
      [](double depth) {
        return nodeToSegment(flatQuad4(), shape::SurfaceType::Quad4, Vector3d(0.21, -0.33, -depth),
                             0, 0, 0);
      },
      4e-3);
}

TEST(NormalTangent, NodeToSegmentCurvedIsExactToSecondOrderInGap) {
  // The curved master passes below the slave point at about z = -0.0098.
  expectNormalTangentExactUpToSecondOrder(
      [](double depth) {
        return nodeToSegment(curvedQuad9(), shape::SurfaceType::Quad9,
                             Vector3d(0.27, 0.18, -0.0098 - depth), 0, 0, 0);
      },
      4e-3);
}

TEST(NormalTangent, SegmentToSegmentCurvedWithConstantAreaIsExactToSecondOrderInGap) {
  const PointCase probe =
      segmentToSegment(curvedQuad9(), shape::SurfaceType::Quad9, 0, 0, 0, true, 0.0);
  const double surfaceHeight = evaluatePoint(probe.setup, probe.nodes).kinematics.gap;
  expectNormalTangentExactUpToSecondOrder(
      [&](double depth) {
        return segmentToSegment(curvedQuad9(), shape::SurfaceType::Quad9, 0, 0, 0, true,
                                depth + surfaceHeight);
      },
      4e-3);
}

// The smoothed Quad4 master (Nagata patch): the same second-order exactness, now with the
// curvature h_ij of the patch on a linear segment.
TEST(NormalTangent, NodeToSegmentSmoothQuad4IsExactToSecondOrderInGap) {
  const PointCase probe = nodeToSegment(curvedQuad4(), shape::SurfaceType::Quad4,
                                        Vector3d(0.27, 0.18, 0), 0, 0, 0, &kSmoothNormals);
  const double surfaceHeight = -evaluatePoint(probe.setup, probe.nodes).kinematics.gap;
  expectNormalTangentExactUpToSecondOrder(
      [&](double depth) {
        return nodeToSegment(curvedQuad4(), shape::SurfaceType::Quad4,
                             Vector3d(0.27, 0.18, surfaceHeight - depth), 0, 0, 0, &kSmoothNormals);
      },
      4e-3);
}

TEST(NormalTangent, SegmentToSegmentSmoothQuad4WithConstantAreaIsExactToSecondOrderInGap) {
  const PointCase probe = segmentToSegment(curvedQuad4(), shape::SurfaceType::Quad4, 0, 0, 0, true,
                                           0.0, &kSmoothNormals);
  const double surfaceHeight = evaluatePoint(probe.setup, probe.nodes).kinematics.gap;
  expectNormalTangentExactUpToSecondOrder(
      [&](double depth) {
        return segmentToSegment(curvedQuad4(), shape::SurfaceType::Quad4, 0, 0, 0, true,
                                depth + surfaceHeight, &kSmoothNormals);
      },
      4e-3);
}

// On the smoothed linear segment the curvature part is needed for that exactness (on the
// faceted one h_ij = 0 and it is skipped): guards against a smoothing that does not reach the
// tangent.
TEST(NormalTangent, CurvaturePartMattersOnSmoothQuad4) {
  const PointCase probe = nodeToSegment(curvedQuad4(), shape::SurfaceType::Quad4,
                                        Vector3d(0.27, 0.18, 0), 0, 0, 0, &kSmoothNormals);
  const double surfaceHeight = -evaluatePoint(probe.setup, probe.nodes).kinematics.gap;
  const PointCase c =
      nodeToSegment(curvedQuad4(), shape::SurfaceType::Quad4,
                    Vector3d(0.27, 0.18, surfaceHeight - 0.01), 0, 0, 0, &kSmoothNormals);
  TangentParts noCurvature;
  noCurvature.normalCurvature = false;
  const MatrixXd reference = finiteDifferenceTangent(c);
  const double without = relativeError(tangent(c, TangentMode::Paper, noCurvature), reference);
  const double with = relativeError(tangent(c, TangentMode::Paper, {}), reference);
  EXPECT_GT(without, 1e-3);
  EXPECT_LT(with, 0.05 * without);
}

// Without the rotational and curvature parts the normal tangent is not exact on a curved
// master: the parts matter (guards against a test that cannot fail).
TEST(NormalTangent, MainPartAloneIsNotExactOnCurvedMaster) {
  const PointCase c =
      nodeToSegment(curvedQuad9(), shape::SurfaceType::Quad9, kSlaveBelowCurved, 0, 0, 0);
  TangentParts mainOnly;
  mainOnly.normalRotational = mainOnly.normalCurvature = false;
  EXPECT_GT(relativeError(tangent(c, TangentMode::Paper, mainOnly), finiteDifferenceTangent(c)),
            1e-4);
}

// ---- the exact tangent matches finite differences for every kind and state ------------------

struct ExactCase {
  const char* name;
  PointCase c;
  ContactState expected;
};

TEST(ExactTangent, MatchesFiniteDifferencesForAllKindsAndStates) {
  static const RigidSurface flatSurface = plane();
  static const RigidSurface curvedSurface = parabolicCylinder();
  const ExactCase cases[] = {
      {"nts flat stick",
       nodeToSegment(flatQuad4(), shape::SurfaceType::Quad4, kSlaveBelowFlat, 0.3, 1e-3, 0.5),
       ContactState::Stick},
      {"nts flat slip",
       nodeToSegment(flatQuad4(), shape::SurfaceType::Quad4, kSlaveBelowFlat, 0.3, 5e-2, 0.5),
       ContactState::Slip},
      {"nts curved stick",
       nodeToSegment(curvedQuad9(), shape::SurfaceType::Quad9, kSlaveBelowCurved, 0.5, 1e-3, 1.0),
       ContactState::Stick},
      {"nts curved slip",
       nodeToSegment(curvedQuad9(), shape::SurfaceType::Quad9, kSlaveBelowCurved, 0.3, 5e-2, 4.0),
       ContactState::Slip},
      {"sts flat stick",
       segmentToSegment(flatQuad4(), shape::SurfaceType::Quad4, 0.5, 1e-3, 1.0, false),
       ContactState::Stick},
      {"sts curved slip",
       segmentToSegment(curvedQuad9(), shape::SurfaceType::Quad9, 0.3, 5e-2, 2.0, false, 0.03),
       ContactState::Slip},
      {"nts smooth stick",
       nodeToSegment(curvedQuad4(), shape::SurfaceType::Quad4, kSlaveBelowCurved, 0.5, 1e-3, 1.0,
                     &kSmoothNormals),
       ContactState::Stick},
      {"nts smooth slip",
       nodeToSegment(curvedQuad4(), shape::SurfaceType::Quad4, kSlaveBelowCurved, 0.3, 5e-2, 4.0,
                     &kSmoothNormals),
       ContactState::Slip},
      {"sts smooth stick",
       segmentToSegment(curvedQuad4(), shape::SurfaceType::Quad4, 0.5, 1e-3, 1.0, false, 0.03,
                        &kSmoothNormals),
       ContactState::Stick},
      {"sts smooth slip",
       segmentToSegment(curvedQuad4(), shape::SurfaceType::Quad4, 0.3, 5e-2, 2.0, false, 0.03,
                        &kSmoothNormals),
       ContactState::Slip},
      {"stas plane stick", analyticalSurface(flatSurface, 0.5, 1e-3, 1.0), ContactState::Stick},
      {"stas parabola slip", analyticalSurface(curvedSurface, 0.3, 5e-2, 2.0), ContactState::Slip},
  };
  for (const ExactCase& e : cases) {
    SCOPED_TRACE(e.name);
    ASSERT_EQ(stateOf(e.c), e.expected);
    EXPECT_LT(relativeError(tangent(e.c, TangentMode::Exact, {}), finiteDifferenceTangent(e.c)),
              1e-6);
  }
}

// ---- integration=segments (issue 16, part 1): a slave segment split by a master edge --------

// Two flat master Quad4 segments (normal +z) sharing the edge from (0.1, -0.9) to (0.05, 1.1),
// which crosses the slave segment of slaveQuad4.
NodeMatrix<double> masterLeftOfEdge() {
  NodeMatrix<double> nodes(3, 4);
  nodes << -2.0, 0.1, 0.05, -2.1,  //
      -1.0, -0.9, 1.1, 0.8,        //
      0, 0, 0, 0;
  return nodes;
}

NodeMatrix<double> masterRightOfEdge() {
  NodeMatrix<double> nodes(3, 4);
  nodes << 0.1, 2.0, 2.1, 0.05,  //
      -0.9, -1.0, 1.0, 1.1,      //
      0, 0, 0, 0;
  return nodes;
}

// The segmented points of the slave: each is an ordinary STS point, so the paper's normal part
// (frictionless, ds constant) is exact up to O(g^2) and the exact tangent matches central
// differences, in stick and in slip, on either side of the master edge.
TEST(SegmentedSts, PointsOfASlaveSegmentSplitByAMasterEdgeHaveTheKernelsTangents) {
  constexpr double kDepth = 0.003;
  const NodeMatrix<double> masters[2] = {masterLeftOfEdge(), masterRightOfEdge()};
  const NodeMatrix<double> slave = slaveQuad4(kDepth);
  std::vector<Polygon2> images;
  for (const NodeMatrix<double>& m : masters) {
    const std::optional<Polygon2> image = masterImage(shape::SurfaceType::Quad4, slave, m);
    ASSERT_TRUE(image.has_value());
    images.push_back(*image);
  }
  const std::vector<SegmentPoint> points = segmentPoints(images, 2);
  int onSide[2] = {0, 0};
  int stick = 0, slip = 0;
  for (const SegmentPoint& p : points) {
    SCOPED_TRACE(testing::Message() << "point " << p.xi.transpose() << " on master " << p.image);
    ASSERT_GE(p.image, 0);
    ++onSide[p.image];
    const NodeMatrix<double>& master = masters[p.image];
    // The slave is slightly warped: penetrate by `depth` at this point (as in the STS test
    // above).
    const PointCase probe = segmentToSegment(master, shape::SurfaceType::Quad4, 0, 0, 0, true, 0.0,
                                             nullptr, p.xi, p.weight);
    const double height = evaluatePoint(probe.setup, probe.nodes).kinematics.gap;
    expectNormalTangentExactUpToSecondOrder(
        [&](double depth) {
          return segmentToSegment(master, shape::SurfaceType::Quad4, 0, 0, 0, true, depth + height,
                                  nullptr, p.xi, p.weight);
        },
        4e-3);
    for (const auto& [friction, slipScale, traction] :
         {std::tuple{0.5, 1e-3, 1.0}, std::tuple{0.3, 5e-2, 2.0}}) {
      const PointCase c = segmentToSegment(master, shape::SurfaceType::Quad4, friction, slipScale,
                                           traction, false, kDepth, nullptr, p.xi, p.weight);
      const ContactState state = stateOf(c);
      ASSERT_NE(state, ContactState::Open);
      (state == ContactState::Stick ? stick : slip) += 1;
      EXPECT_LT(relativeError(tangent(c, TangentMode::Exact, {}), finiteDifferenceTangent(c)),
                1e-6);
    }
  }
  // The edge splits the slave (3-point rules on the pieces, not the 4 Gauss points), both
  // masters get points, and both states were exercised.
  EXPECT_GT(points.size(), 4u);
  EXPECT_GT(onSide[0], 0);
  EXPECT_GT(onSide[1], 0);
  EXPECT_GT(stick, 0);
  EXPECT_GT(slip, 0);
}

// ---- a slave point beyond the master's free edge with edge=fade (issue 14) -------------------

// The fading factor is 1 up to the tolerance, 0 from the end of the band, and C1 at both ends
// (one-sided differences of the factor vanish there to O(h)).
TEST(FreeEdgeFactor, FallsFromOneToZeroContinuouslyAcrossTheBand) {
  const unsigned edge1 = 1u << 1;  // xi1 = 1
  const auto at = [&](double xi1) { return freeEdgeFactor<double>(Vector2d(xi1, 0.3), edge1); };
  const double start = 1 + kFreeEdgeTolerance, end = start + kFreeEdgeBand, h = 1e-7;
  EXPECT_EQ(at(1.0), 1.0);
  EXPECT_EQ(at(start), 1.0);
  EXPECT_NEAR(at(start + h), 1.0, 1e-12);
  EXPECT_NEAR(at(end - h), 0.0, 1e-12);
  EXPECT_EQ(at(end), 0.0);
  EXPECT_NEAR(at(start + kFreeEdgeBand / 2), 0.5, 1e-12);               // 1 - 3/4 + 2/8
  EXPECT_EQ(freeEdgeFactor<double>(Vector2d(1.5, 0.3), 1u << 3), 1.0);  // only free edges count
}

// NTS, flat master whose edge xi1 = 1 is free, slave node in the band beyond it: the force is a
// fraction of the full one, and the exact tangent (which differentiates the fading factor through
// the projection parameter) matches central differences, in stick and in slip.
TEST(FreeEdgeFactor, ExactTangentMatchesFiniteDifferencesInTheBand) {
  const Vector3d beyondEdge(1.08, 0.1, -0.002);
  for (const double slip : {1e-3, 5e-2}) {
    SCOPED_TRACE(slip);
    PointCase c = nodeToSegment(flatQuad4(), shape::SurfaceType::Quad4, beyondEdge, 0.3, slip, 0.5);
    const double excess = c.setup.parameter[0] - 1;
    ASSERT_GT(excess, kFreeEdgeTolerance + 0.2 * kFreeEdgeBand);
    ASSERT_LT(excess, kFreeEdgeTolerance + 0.8 * kFreeEdgeBand);
    const Vector3d full = evaluatePoint(c.setup, c.nodes).force.tail<3>();
    c.setup.layout.freeEdges = 1u << 1;
    const PointEvaluation faded = evaluatePoint(c.setup, c.nodes);
    ASSERT_EQ(faded.response.state, slip > 1e-2 ? ContactState::Slip : ContactState::Stick);
    const double share = freeEdgeFactor<double>(faded.xi, 1u << 1);
    EXPECT_GT(share, 0.05);
    EXPECT_LT(share, 0.95);
    EXPECT_LT((faded.force.tail<3>() - share * full).norm(), 1e-12 * full.norm());
    EXPECT_LT(relativeError(tangent(c, TangentMode::Exact, {}), finiteDifferenceTangent(c)), 1e-6);
  }
}

// ---- the paper's tangential parts: symmetric in stick, error vanishing with the increment ---

TEST(PaperTangent, StickTangentIsSymmetric) {
  const PointCase c =
      nodeToSegment(curvedQuad9(), shape::SurfaceType::Quad9, kSlaveBelowCurved, 0.5, 1e-3, 1.0);
  ASSERT_EQ(stateOf(c), ContactState::Stick);
  const MatrixXd K = tangent(c, TangentMode::Paper, {});
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
}

TEST(PaperTangent, StickTangentIsSymmetricOnSmoothMaster) {
  const PointCase c = nodeToSegment(curvedQuad4(), shape::SurfaceType::Quad4, kSlaveBelowCurved,
                                    0.5, 1e-3, 1.0, &kSmoothNormals);
  ASSERT_EQ(stateOf(c), ContactState::Stick);
  const MatrixXd K = tangent(c, TangentMode::Paper, {});
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
}

TEST(PaperTangent, SlideTangentIsUnsymmetric) {
  const PointCase c =
      nodeToSegment(curvedQuad9(), shape::SurfaceType::Quad9, kSlaveBelowCurved, 0.3, 5e-2, 4.0);
  ASSERT_EQ(stateOf(c), ContactState::Slip);
  const MatrixXd K = tangent(c, TangentMode::Paper, {});
  EXPECT_GT((K - K.transpose()).norm(), 1e-3 * K.norm());
}

// The paper's tangential parts linearize the continuous evolution equations (74) on the tangent
// plane (section 4): against the discrete algorithm (77)-(79) they differ by terms of the order
// of the load increment, i.e. of the slip Delta rho, of the penetration g (delta xi is taken at
// xi^3 = 0, eq. (42) instead of (41)) and of the traction (|T| <= mu eps_N |g|). Scale all three
// with an increment s and assert that the difference falls at first order.
struct IncrementScaling {
  const char* name;
  std::function<PointCase(double)> make;
  ContactState state;
};

void expectFirstOrderInIncrement(const IncrementScaling& scaling) {
  SCOPED_TRACE(scaling.name);
  const double increments[3] = {4e-3, 2e-3, 1e-3};
  double errors[3];
  for (int k = 0; k < 3; ++k) {
    const PointCase c = scaling.make(increments[k]);
    ASSERT_EQ(stateOf(c), scaling.state);
    errors[k] = relativeError(tangent(c, TangentMode::Paper, {}), finiteDifferenceTangent(c));
  }
  for (int k = 0; k < 2; ++k) {
    const double order = std::log2(errors[k] / errors[k + 1]);
    EXPECT_GT(order, 0.8) << errors[0] << " " << errors[1] << " " << errors[2];
    EXPECT_LT(order, 1.3) << errors[0] << " " << errors[1] << " " << errors[2];
  }
}

// Slip multiplier: small enough to stick, large enough to slide.
constexpr double kStickSlip = 0.2;
constexpr double kSlideSlip = 5.0;
constexpr double kFriction = 0.5;
// Previous traction, as a fraction of the Coulomb limit mu eps_N s.
constexpr double kTractionFraction = 0.2;

PointCase nodeToSegmentScaled(bool curved, double s, double slip) {
  const double surface = curved ? -0.0098 : 0.0;  // master height below the slave point
  const Vector3d point = curved ? Vector3d(0.27, 0.18, surface - s) : Vector3d(0.21, -0.33, -s);
  return nodeToSegment(curved ? curvedQuad9() : flatQuad4(),
                       curved ? shape::SurfaceType::Quad9 : shape::SurfaceType::Quad4, point,
                       kFriction, slip * s, kTractionFraction * kFriction * kPenaltyNormal * s);
}

// The smoothed Quad4 master: slave node at depth s below the patch.
PointCase nodeToSegmentSmoothScaled(double s, double slip) {
  const PointCase probe = nodeToSegment(curvedQuad4(), shape::SurfaceType::Quad4,
                                        Vector3d(0.27, 0.18, 0), 0, 0, 0, &kSmoothNormals);
  const double surface = -evaluatePoint(probe.setup, probe.nodes).kinematics.gap;
  return nodeToSegment(curvedQuad4(), shape::SurfaceType::Quad4, Vector3d(0.27, 0.18, surface - s),
                       kFriction, slip * s, kTractionFraction * kFriction * kPenaltyNormal * s,
                       &kSmoothNormals);
}

PointCase segmentToSegmentSmoothScaled(double s, double slip) {
  const PointCase probe = segmentToSegment(curvedQuad4(), shape::SurfaceType::Quad4, 0, 0, 0, true,
                                           0.0, &kSmoothNormals);
  const double height = evaluatePoint(probe.setup, probe.nodes).kinematics.gap;
  return segmentToSegment(curvedQuad4(), shape::SurfaceType::Quad4, kFriction, slip * s,
                          kTractionFraction * kFriction * kPenaltyNormal * s, true, height + s,
                          &kSmoothNormals);
}

PointCase segmentToSegmentScaled(double s, double slip) {
  const PointCase probe =
      segmentToSegment(curvedQuad9(), shape::SurfaceType::Quad9, 0, 0, 0, true, 0.0);
  const double height = evaluatePoint(probe.setup, probe.nodes).kinematics.gap;
  return segmentToSegment(curvedQuad9(), shape::SurfaceType::Quad9, kFriction, slip * s,
                          kTractionFraction * kFriction * kPenaltyNormal * s, true, height + s);
}

PointCase analyticalSurfaceScaled(const RigidSurface& surface, double s, double slip) {
  PointCase c = analyticalSurface(surface, kFriction, slip * s,
                                  kTractionFraction * kFriction * kPenaltyNormal * s);
  c.setup.surfaceOffset.setZero();
  const double gapWithoutOffset = evaluatePoint(c.setup, c.nodes).kinematics.gap;
  c.setup.surfaceOffset.z() = gapWithoutOffset + s;  // the master normal points along -z
  c.setup.history.surfaceOffset = c.setup.surfaceOffset;
  return c;
}

TEST(PaperTangent, TangentialPartsDifferFromDiscreteAlgorithmAtFirstOrderInIncrement) {
  // The master segment of the STAS cases is not exactly planar; this plane is parallel to its
  // tangent plane at the Gauss point.
  static const RigidSurface parallelPlane = [] {
    // The probe keeps a pointer to its surface: the surface must outlive it (ASan).
    const RigidSurface probeSurface = plane(0.0);
    PointCase probe = analyticalSurface(probeSurface, 0, 0, 0);
    RigidSurface s = plane(0.0);
    s.normal = -evaluatePoint(probe.setup, probe.nodes).kinematics.frame.normal;
    return s;
  }();
  const IncrementScaling cases[] = {
      {"nts flat stick", [](double s) { return nodeToSegmentScaled(false, s, kStickSlip); },
       ContactState::Stick},
      {"nts flat slide", [](double s) { return nodeToSegmentScaled(false, s, kSlideSlip); },
       ContactState::Slip},
      {"nts curved stick", [](double s) { return nodeToSegmentScaled(true, s, kStickSlip); },
       ContactState::Stick},
      {"nts curved slide", [](double s) { return nodeToSegmentScaled(true, s, kSlideSlip); },
       ContactState::Slip},
      {"sts curved stick", [](double s) { return segmentToSegmentScaled(s, kStickSlip); },
       ContactState::Stick},
      {"sts curved slide", [](double s) { return segmentToSegmentScaled(s, kSlideSlip); },
       ContactState::Slip},
      {"nts smooth stick", [](double s) { return nodeToSegmentSmoothScaled(s, kStickSlip); },
       ContactState::Stick},
      {"nts smooth slide", [](double s) { return nodeToSegmentSmoothScaled(s, kSlideSlip); },
       ContactState::Slip},
      {"sts smooth stick", [](double s) { return segmentToSegmentSmoothScaled(s, kStickSlip); },
       ContactState::Stick},
      {"sts smooth slide", [](double s) { return segmentToSegmentSmoothScaled(s, kSlideSlip); },
       ContactState::Slip},
      {"stas parallel plane stick",
       [](double s) { return analyticalSurfaceScaled(parallelPlane, s, kStickSlip); },
       ContactState::Stick},
      {"stas parallel plane slide",
       [](double s) { return analyticalSurfaceScaled(parallelPlane, s, kSlideSlip); },
       ContactState::Slip},
  };
  for (const IncrementScaling& scaling : cases) expectFirstOrderInIncrement(scaling);
}

// STAS measures the gap along the master normal, eq. (117), and integrates at fixed master Gauss
// points: the rigid point slides along the surface, so delta g = -(delta rho) . nu / (n . nu)
// (nu: the rigid surface's normal), and with xi fixed only the N delta n and T_i delta rho^i
// halves of the rotational parts remain. Where the rigid surface is tilted against the master
// segment (a faceted master on a curved rigid surface) the paper's parts must therefore stay as
// close to the exact tangent as on a parallel plane: the remaining difference is the first-order
// one in the increment, not one proportional to the tilt (treating the rigid point like a
// projected slave point, as before, doubled the difference from tilt 0.02 to 0.04).
TEST(PaperTangent, AnalyticalSurfaceDifferenceDoesNotGrowWithTilt) {
  double errors[2];
  const double tilts[2] = {0.04, 0.02};
  const double s = 1e-4;
  for (int k = 0; k < 2; ++k) {
    const RigidSurface tilted = plane(tilts[k]);
    const PointCase c = analyticalSurfaceScaled(tilted, s, kStickSlip);
    ASSERT_EQ(stateOf(c), ContactState::Stick);
    errors[k] = relativeError(tangent(c, TangentMode::Paper, {}), finiteDifferenceTangent(c));
  }
  const double order = std::log2(errors[0] / errors[1]);
  EXPECT_LT(std::abs(order), 0.2) << errors[0] << " " << errors[1];
}

}  // namespace
}  // namespace cc::contact
