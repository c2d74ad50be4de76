// Surface frame, projection and rigid-surface intersection against analytic values and finite
// differences (issue 4, "Verification": frame quantities).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <unsupported/Eigen/AutoDiff>

#include "contact/geometry.hpp"
#include "contact/projection.hpp"
#include "contact/rigid_surface.hpp"

namespace cc::contact {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// A distorted, warped Quad9 segment (curved in both directions).
NodeMatrix<double> curvedQuad9() {
  NodeMatrix<double> nodes(3, 9);
  const double corner[9][2] = {{-1, -1}, {1, -1}, {1, 1},  {-1, 1}, {0, -1},
                               {1, 0},   {0, 1},  {-1, 0}, {0, 0}};
  for (int k = 0; k < 9; ++k) {
    const double x = 1.3 * corner[k][0] + 0.2 * corner[k][1];
    const double y = 0.9 * corner[k][1] - 0.1 * corner[k][0] * corner[k][0];
    nodes.col(k) << x, y, 0.15 * x * x - 0.1 * y * y + 0.05 * x * y;
  }
  return nodes;
}

NodeMatrix<double> warpedQuad4() {
  NodeMatrix<double> nodes(3, 4);
  nodes << -1.1, 0.9, 1.2, -0.8,  //
      -0.9, -1.1, 1.0, 0.8,       //
      0.05, -0.1, 0.12, -0.04;
  return nodes;
}

SurfaceFrame<double> frameAt(shape::SurfaceType type, const NodeMatrix<double>& nodes,
                             Vector2d xi) {
  return surfaceFrame<double>(type, nodes, xi[0], xi[1]);
}

// Parametric derivatives, the Weingarten formula (13) and the Gauss-Codazzi formula (14)
// against central finite differences of the frame itself.
void checkFrameAgainstFiniteDifferences(shape::SurfaceType type, const NodeMatrix<double>& nodes) {
  const Vector2d xi(0.31, -0.42);
  const double h = 1e-6;  // central differences: error O(h^2) ~ 1e-12, round-off ~ eps/h ~ 1e-10
  const double tolerance = 1e-8;
  const SurfaceFrame<double> f = frameAt(type, nodes, xi);
  for (int i = 0; i < 2; ++i) {
    Vector2d step = Vector2d::Zero();
    step[i] = h;
    const SurfaceFrame<double> plus = frameAt(type, nodes, xi + step);
    const SurfaceFrame<double> minus = frameAt(type, nodes, xi - step);
    EXPECT_LT(((plus.rho - minus.rho) / (2 * h) - f.rhoCov[i]).norm(), tolerance);
    for (int j = 0; j < 2; ++j) {
      EXPECT_LT(((plus.rhoCov[j] - minus.rhoCov[j]) / (2 * h) - f.second(i, j)).norm(), tolerance);
    }
    // Weingarten, eq. (13): n_,i = -h_i^k rho_k.
    const Vector3d normalDerivative = (plus.normal - minus.normal) / (2 * h);
    const Vector3d weingarten =
        -(f.curvatureMixed(i, 0) * f.rhoCov[0] + f.curvatureMixed(i, 1) * f.rhoCov[1]);
    EXPECT_LT((normalDerivative - weingarten).norm(), tolerance);
  }
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      // Gauss-Codazzi, eq. (14): rho_ij = Gamma^k_ij rho_k + h_ij n.
      const Vector3d decomposed = f.christoffel[0](i, j) * f.rhoCov[0] +
                                  f.christoffel[1](i, j) * f.rhoCov[1] +
                                  f.curvature(i, j) * f.normal;
      EXPECT_LT((decomposed - f.second(i, j)).norm(), 1e-13);
    }
  }
  EXPECT_LT((f.metric * f.inverseMetric - Eigen::Matrix2d::Identity()).norm(), 1e-14);
  EXPECT_NEAR(f.rhoContra[0].dot(f.rhoCov[1]), 0.0, 1e-14);
  EXPECT_NEAR(f.rhoContra[1].dot(f.rhoCov[1]), 1.0, 1e-14);
}

TEST(SurfaceFrame, DistortedQuad4AgainstFiniteDifferences) {
  checkFrameAgainstFiniteDifferences(shape::SurfaceType::Quad4, warpedQuad4());
}

TEST(SurfaceFrame, CurvedQuad9AgainstFiniteDifferences) {
  checkFrameAgainstFiniteDifferences(shape::SurfaceType::Quad9, curvedQuad9());
}

// Sphere of radius R parametrized by (theta, phi): a = diag(R^2, R^2 sin^2 theta),
// h_ij = -a_ij / R with the outward normal, Gamma^theta_phiphi = -sin cos, Gamma^phi_thetaphi =
// cot theta; the mean and Gauss curvature follow.
TEST(SurfaceFrame, SphereAnalytic) {
  const double R = 2.5, theta = 0.7, phi = 0.3;
  const double st = std::sin(theta), ct = std::cos(theta), sp = std::sin(phi), cp = std::cos(phi);
  const Vector3d rho = R * Vector3d(st * cp, st * sp, ct);
  // Order (theta, phi) gives rho_theta x rho_phi along the outward radius.
  const std::array<Vector3d, 2> rhoCov = {R * Vector3d(ct * cp, ct * sp, -st),
                                          R * Vector3d(-st * sp, st * cp, 0)};
  const std::array<Vector3d, 3> rhoSecond = {R * Vector3d(-st * cp, -st * sp, -ct),
                                             R * Vector3d(-ct * sp, ct * cp, 0),
                                             R * Vector3d(-st * cp, -st * sp, 0)};
  const SurfaceFrame<double> f = frameFromDerivatives(rho, rhoCov, rhoSecond);
  EXPECT_NEAR(f.metric(0, 0), R * R, 1e-13);
  EXPECT_NEAR(f.metric(1, 1), R * R * st * st, 1e-13);
  EXPECT_NEAR(f.metric(0, 1), 0.0, 1e-13);
  EXPECT_LT((f.normal - rho / R).norm(), 1e-14);
  EXPECT_LT((f.curvature + f.metric / R).norm(), 1e-13);
  EXPECT_LT((f.curvatureMixed + Eigen::Matrix2d::Identity() / R).norm(), 1e-14);
  EXPECT_NEAR(f.christoffel[0](1, 1), -st * ct, 1e-14);
  EXPECT_NEAR(f.christoffel[1](0, 1), ct / st, 1e-14);
  EXPECT_NEAR(f.christoffel[1](1, 0), ct / st, 1e-14);
  EXPECT_NEAR(f.christoffel[0](0, 0), 0.0, 1e-14);
  EXPECT_NEAR(f.areaElement, R * R * st, 1e-13);
}

// Circular cylinder of radius R about z, parametrized by (phi, z): a = diag(R^2, 1),
// h_phiphi = -R (outward normal), all Christoffel symbols zero.
TEST(SurfaceFrame, CylinderAnalytic) {
  const double R = 0.8, phi = 1.1, z = 0.4;
  const Vector3d rho(R * std::cos(phi), R * std::sin(phi), z);
  const std::array<Vector3d, 2> rhoCov = {Vector3d(-R * std::sin(phi), R * std::cos(phi), 0),
                                          Vector3d(0, 0, 1)};
  const std::array<Vector3d, 3> rhoSecond = {Vector3d(-R * std::cos(phi), -R * std::sin(phi), 0),
                                             Vector3d::Zero(), Vector3d::Zero()};
  const SurfaceFrame<double> f = frameFromDerivatives(rho, rhoCov, rhoSecond);
  EXPECT_NEAR(f.metric(0, 0), R * R, 1e-14);
  EXPECT_NEAR(f.metric(1, 1), 1.0, 1e-14);
  EXPECT_LT((f.normal - Vector3d(std::cos(phi), std::sin(phi), 0)).norm(), 1e-14);
  EXPECT_NEAR(f.curvature(0, 0), -R, 1e-14);
  EXPECT_NEAR(f.curvatureMixed(0, 0), -1.0 / R, 1e-14);
  for (int k = 0; k < 2; ++k) EXPECT_LT(f.christoffel[k].norm(), 1e-14);
}

// A Quad9 segment with nodes on the parabolic cylinder z = c x^2 reproduces it exactly (the
// surface is quadratic in xi), so its frame must equal the analytic one of examples 6.2/6.3:
// a_11 = hx^2 (1 + 4c^2x^2), h_11 = 2c hx^2 / sqrt(1 + 4c^2x^2), Gamma^1_11 = 4c^2 x hx / (1 +
// 4c^2x^2), everything else of the y direction trivial.
TEST(SurfaceFrame, ParabolicCylinderQuad9Analytic) {
  const double c = 0.03, x0 = 4.0, hx = 0.5, hy = 0.25;
  const double corner[9][2] = {{-1, -1}, {1, -1}, {1, 1},  {-1, 1}, {0, -1},
                               {1, 0},   {0, 1},  {-1, 0}, {0, 0}};
  NodeMatrix<double> nodes(3, 9);
  for (int k = 0; k < 9; ++k) {
    const double x = x0 + hx * corner[k][0];
    nodes.col(k) << x, hy * corner[k][1], c * x * x;
  }
  const Vector2d xi(0.37, -0.6);
  const SurfaceFrame<double> f = frameAt(shape::SurfaceType::Quad9, nodes, xi);
  const double x = x0 + hx * xi[0];
  const double slope2 = 1 + 4 * c * c * x * x;
  EXPECT_NEAR(f.rho.z(), c * x * x, 1e-14);
  EXPECT_NEAR(f.metric(0, 0), hx * hx * slope2, 1e-13);
  EXPECT_NEAR(f.metric(1, 1), hy * hy, 1e-14);
  EXPECT_NEAR(f.metric(0, 1), 0.0, 1e-14);
  // n = rho_1 x rho_2 / |.| points to -x and +z here: (-2cx, 0, 1) / sqrt(slope2).
  EXPECT_LT((f.normal - Vector3d(-2 * c * x, 0, 1) / std::sqrt(slope2)).norm(), 1e-14);
  EXPECT_NEAR(f.curvature(0, 0), 2 * c * hx * hx / std::sqrt(slope2), 1e-14);
  EXPECT_NEAR(f.curvature(1, 1), 0.0, 1e-14);
  EXPECT_NEAR(f.christoffel[0](0, 0), 4 * c * c * x * hx / slope2, 1e-14);
  EXPECT_NEAR(f.christoffel[1](0, 0), 0.0, 1e-14);
}

TEST(Projection, ConvergesOrthogonallyOnCurvedSegment) {
  const NodeMatrix<double> nodes = curvedQuad9();
  const Vector3d point(0.4, -0.3, 0.35);
  const ProjectionResult p =
      closestPointProjection(shape::SurfaceType::Quad9, nodes, point, Vector2d::Zero());
  ASSERT_TRUE(p.converged);
  EXPECT_TRUE(p.inside());
  EXPECT_LE(p.iterations, 8);
  const SurfaceFrame<double> f = frameAt(shape::SurfaceType::Quad9, nodes, p.xi);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR((point - f.rho).dot(f.rhoCov[i]), 0.0, 1e-13);
  // The distance vector is along the normal.
  EXPECT_NEAR(std::abs((point - f.rho).normalized().dot(f.normal)), 1.0, 1e-13);
}

TEST(Projection, ReportsParameterOutsideSegment) {
  const NodeMatrix<double> nodes = warpedQuad4();
  const ProjectionResult p = closestPointProjection(shape::SurfaceType::Quad4, nodes,
                                                    Vector3d(1.9, 0.1, 0.2), Vector2d::Zero());
  ASSERT_TRUE(p.converged);
  EXPECT_FALSE(p.inside());
  EXPECT_GT(p.xi[0], 1.0);
}

// A thin segment far from the origin: 5.6 long, 0.094 wide (the Cattaneo-Mindlin cylinder deck's
// master strips, one element thick) and shifted by 1000. The parameter across the strip is known
// to eps |r| / 0.047 ~ 5e-12 only, above the projection's 1e-13 tolerance: Newton's steps stalled
// there and the projection reported a breakdown (the deck's run stopped at t = 1.4). On this flat,
// slightly skewed strip the closest point solves a 2 x 2 linear system, the independent reference.
TEST(Projection, ConvergesToTheRoundoffOfTheCoordinatesOnAThinSegmentFarAway) {
  const Vector3d shift(1000.0, -700.0, 400.0);
  const Vector3d corner = shift, along(5.6, 0.0, 0.3), across(0.01, 0.094, 0.0);
  NodeMatrix<double> nodes(3, 4);
  nodes.col(0) = corner;
  nodes.col(1) = corner + along;
  nodes.col(2) = corner + along + across;
  nodes.col(3) = corner + across;
  for (double a : {0.1, 0.37, 0.5, 0.83}) {
    for (double b : {0.05, 0.5, 0.71, 0.98}) {
      // A point above (a, b) of the strip, off its plane by 0.2 along the normal.
      const Vector3d normal = along.cross(across).normalized();
      const Vector3d point = corner + a * along + b * across + 0.2 * normal;
      const ProjectionResult p =
          closestPointProjection(shape::SurfaceType::Quad4, nodes, point, Vector2d::Zero());
      EXPECT_TRUE(p.converged) << a << " " << b;
      EXPECT_FALSE(p.brokeDown) << a << " " << b;
      // xi = 2 (a, b) - 1 exactly; known to ~1e-11 across the strip here.
      EXPECT_NEAR(p.xi[0], 2 * a - 1, 1e-10);
      EXPECT_NEAR(p.xi[1], 2 * b - 1, 1e-10);
    }
  }
}

// d xi / d x of the differentiable projection against central differences of re-projections.
TEST(Projection, DifferentiableProjectionMatchesFiniteDifferences) {
  using AD = Eigen::AutoDiffScalar<Eigen::VectorXd>;
  const NodeMatrix<double> nodes = curvedQuad9();
  const Vector3d point(0.2, 0.1, 0.3);
  const ProjectionResult base =
      closestPointProjection(shape::SurfaceType::Quad9, nodes, point, Vector2d::Zero());
  ASSERT_TRUE(base.converged);
  const int dofs = 3 * 10;
  NodeMatrix<AD> active(3, 9);
  Vec3<AD> activePoint;
  for (int k = 0; k < 9; ++k) {
    for (int c = 0; c < 3; ++c) active(c, k) = AD(nodes(c, k), dofs, 3 * k + c);
  }
  for (int c = 0; c < 3; ++c) activePoint[c] = AD(point[c], dofs, 27 + c);
  const auto xi = differentiableProjection(shape::SurfaceType::Quad9, active, activePoint, base.xi);
  const double h = 1e-6;
  for (int dof = 0; dof < dofs; ++dof) {
    NodeMatrix<double> plusNodes = nodes, minusNodes = nodes;
    Vector3d plusPoint = point, minusPoint = point;
    if (dof < 27) {
      plusNodes(dof % 3, dof / 3) += h;
      minusNodes(dof % 3, dof / 3) -= h;
    } else {
      plusPoint[dof - 27] += h;
      minusPoint[dof - 27] -= h;
    }
    const Vector2d plus =
        closestPointProjection(shape::SurfaceType::Quad9, plusNodes, plusPoint, base.xi).xi;
    const Vector2d minus =
        closestPointProjection(shape::SurfaceType::Quad9, minusNodes, minusPoint, base.xi).xi;
    const Vector2d finiteDifference = (plus - minus) / (2 * h);
    EXPECT_NEAR(xi[0].derivatives()[dof], finiteDifference[0], 1e-8);
    EXPECT_NEAR(xi[1].derivatives()[dof], finiteDifference[1], 1e-8);
  }
}

RigidSurface makeSurface(RigidSurface::Shape shape) {
  RigidSurface s;
  s.shape = shape;
  s.origin = Vector3d(0.1, -0.2, 0.05);
  s.normal = Vector3d(0, 0, 1);
  s.axis = Vector3d(0, 1, 0);
  s.radius = 1.5;
  s.curvature = 0.05;
  return s;
}

// The gap xi^3 of eq. (117) puts rho + g n on the surface, on its entering side.
TEST(RigidSurface, NormalLineMeetsSurfaceOnEnteringSide) {
  using Shape = RigidSurface::Shape;
  const Vector3d offset(0.0, 0.0, -0.01);
  for (Shape shape : {Shape::Plane, Shape::Sphere, Shape::Cylinder, Shape::ParabolicCylinder}) {
    const RigidSurface s = makeSurface(shape);
    RigidSurface moved = s;
    moved.origin += offset;
    // A master point above the surface with its outward normal pointing down, slightly tilted.
    const double top = shape == Shape::Plane || shape == Shape::ParabolicCylinder ? 0.3 : 1.9;
    const Vector3d rho(0.4, 0.2, top);
    const Vector3d n = Vector3d(0.1, -0.05, -1).normalized();
    const auto gap = normalLineGap<double>(s, offset, rho, n);
    ASSERT_TRUE(gap.has_value()) << static_cast<int>(shape);
    const Vector3d onSurface = rho + *gap * n;
    EXPECT_NEAR(moved.level(onSurface), 0.0, 1e-13) << static_cast<int>(shape);
    EXPECT_LT(moved.outwardNormal(onSurface).dot(n), 0.0) << static_cast<int>(shape);
    EXPECT_GT(*gap, 0.0);  // the point is outside: the gap is open
  }
}

// Example 6.3's closed form: for the parabola x_s = alpha, z_s = c alpha^2 the iteration (122)
// alpha <- (c alpha^2 n1 + n1 x2 - n2 x1) / (2 c alpha n1 - n2) started at alpha = x1 (123)
// converges to the same surface point as our closed-form intersection.
TEST(RigidSurface, ParabolicCylinderMatchesPaperIteration) {
  RigidSurface s = makeSurface(RigidSurface::Shape::ParabolicCylinder);
  s.origin.setZero();
  const double c = s.curvature;
  const Vector3d rho(2.0, 0.0, 0.18);  // in the x-z plane: x1 = x, x2 = z
  const Vector3d n = Vector3d(-0.2, 0, -1).normalized();
  const auto gap = normalLineGap<double>(s, Vector3d::Zero(), rho, n);
  ASSERT_TRUE(gap.has_value());
  double alpha = rho.x();  // eq. (123)
  for (int k = 0; k < 50; ++k) {
    alpha = (c * alpha * alpha * n.x() + n.x() * rho.z() - n.z() * rho.x()) /
            (2 * c * alpha * n.x() - n.z());
  }
  EXPECT_NEAR(alpha, rho.x() + *gap * n.x(), 1e-13);
  EXPECT_NEAR(c * alpha * alpha, rho.z() + *gap * n.z(), 1e-13);
}

TEST(RigidSurface, NormalLineMissingSphereGivesNoContact) {
  const RigidSurface s = makeSurface(RigidSurface::Shape::Sphere);
  const auto gap =
      normalLineGap<double>(s, Vector3d::Zero(), Vector3d(5, 0, 3), Vector3d(0, 0, -1));
  EXPECT_FALSE(gap.has_value());
}

}  // namespace
}  // namespace cc::contact
