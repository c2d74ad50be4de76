// The Coulomb stick domain in the parameter plane of a flat master (Remark 3 of section 3.2):
// with T^(0) = 0 at xi_(0), a point sticks while eps_T^2 a_kl dxi^k dxi^l <= (mu N)^2, an
// ellipse given by the metric a_kl (eq. (81)), not a circle.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "contact/point_evaluation.hpp"

namespace cc::contact {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// A parallelogram segment on a tilted plane: rho(xi) = centre + xi^1 e1 + xi^2 e2 exactly, with
// e1, e2 of different lengths and not orthogonal (a_12 != 0).
const Vector3d kCentre(0.3, -0.2, 0.5);
const Vector3d kE1(1.3, 0.2, 0.4);
const Vector3d kE2(0.5, 0.9, -0.3);

struct EllipseCase {
  PointSetup point;
  NodeMatrix<double> nodes;
  Vector3d normal;
};

EllipseCase makeSetup() {
  EllipseCase s;
  PointLayout& layout = s.point.layout;
  layout.masterType = shape::SurfaceType::Quad4;
  layout.masterCount = 4;
  for (int k = 0; k < 4; ++k) layout.masterLocal[k] = k;
  layout.slaveCount = 1;
  layout.slaveLocal[0] = 4;
  layout.slaveShape[0] = 1.0;
  layout.nodeCount = 5;
  s.point.kind = PointKind::NodeToSegment;
  s.point.slave.nodalArea = 0.8;
  s.point.law = {3.0e3, 2.0e3, 0.4};
  s.point.history.projected = true;
  s.point.history.xi = Vector2d(0.1, -0.2);
  s.point.history.state = ContactState::Stick;
  s.nodes.resize(3, 5);
  const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (int k = 0; k < 4; ++k) s.nodes.col(k) = kCentre + corner[k][0] * kE1 + corner[k][1] * kE2;
  s.normal = kE1.cross(kE2).normalized();
  s.point.parameter = s.point.history.xi;
  return s;
}

// State of the point whose projection lies at xi = xi0 + r d, penetration g.
ContactState stateAt(EllipseCase& s, const Vector2d& direction, double r, double g) {
  const Vector2d xi = s.point.history.xi + r * direction;
  s.nodes.col(4) = kCentre + xi[0] * kE1 + xi[1] * kE2 - g * s.normal;
  s.point.parameter = xi;
  return evaluatePoint(s.point, s.nodes).response.state;
}

TEST(FrictionLaw, StickDomainIsTheMetricEllipse) {
  const double g = 2e-3;
  EllipseCase s = makeSetup();
  Eigen::Matrix2d metric;
  metric << kE1.dot(kE1), kE1.dot(kE2), kE2.dot(kE1), kE2.dot(kE2);
  const double limit = s.point.law.friction * s.point.law.penaltyNormal * g;  // mu |N|
  // The ellipse is not a circle: its axes differ clearly.
  const Eigen::Vector2d axes = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(metric).eigenvalues();
  ASSERT_GT(std::sqrt(axes[1] / axes[0]), 1.5);
  for (int k = 0; k < 16; ++k) {
    const double theta = 2 * std::numbers::pi * k / 16;
    const Vector2d d(std::cos(theta), std::sin(theta));
    const double expected = limit / (s.point.law.penaltyTangential * std::sqrt(d.dot(metric * d)));
    // Bisection on the stick/slip state between 0 (stick) and 2x the ellipse radius (slip).
    double inner = 0, outer = 2 * expected;
    ASSERT_EQ(stateAt(s, d, outer, g), ContactState::Slip);
    for (int step = 0; step < 60; ++step) {
      const double middle = 0.5 * (inner + outer);
      (stateAt(s, d, middle, g) == ContactState::Stick ? inner : outer) = middle;
    }
    // The stick test has a relative tolerance of 1e-9 on mu |N| (kConeTolerance).
    EXPECT_NEAR(inner / expected, 1.0, 1e-8) << "direction " << theta;
  }
}

}  // namespace
}  // namespace cc::contact
