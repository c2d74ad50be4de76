// Segment-exact STS integration (issue 16, part 1; contact/segmentation.hpp): the weights of a
// segmented slave segment integrate its area exactly whatever the master overlap, the covered
// share is the overlapped area, and an unsplit segment keeps today's Gauss rule.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "contact/segmentation.hpp"
#include "fem/quadrature.hpp"

namespace cc::contact {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// A flat, distorted slave Quad4 in a tilted plane through `origin`, with in-plane axes e1, e2.
struct TiltedPlane {
  Vector3d origin{0.3, -0.2, 0.1};
  Vector3d e1 = Vector3d(1, 0, 0.2).normalized();
  Vector3d e2 =
      Vector3d(1, 0, 0.2).cross(Vector3d(0, 1, 0.3)).cross(Vector3d(1, 0, 0.2)).normalized();
  Vector3d normal() const { return e1.cross(e2); }
  Vector3d at(double u, double v, double offset = 0) const {
    return origin + u * e1 + v * e2 + offset * normal();
  }
};

NodeMatrix<double> quad(const TiltedPlane& plane, const std::array<Vector2d, 4>& corners,
                        double offset = 0) {
  NodeMatrix<double> nodes(3, 4);
  for (int k = 0; k < 4; ++k) nodes.col(k) = plane.at(corners[k][0], corners[k][1], offset);
  return nodes;
}

// The slave: counter-clockwise in the plane (normal +n), not a parallelogram.
NodeMatrix<double> slaveQuad(const TiltedPlane& plane) {
  return quad(plane, {Vector2d(-0.5, -0.45), Vector2d(0.55, -0.4), Vector2d(0.6, 0.5),
                      Vector2d(-0.45, 0.55)});
}

double flatQuadArea(const NodeMatrix<double>& nodes) {
  return 0.5 * (nodes.col(2) - nodes.col(0)).cross(nodes.col(3) - nodes.col(1)).norm();
}

double areaElement(const NodeMatrix<double>& nodes, const Vector2d& xi) {
  const shape::SurfaceShape<double> shape =
      shape::surfaceShape(shape::SurfaceType::Quad4, xi[0], xi[1]);
  Vector3d point;
  std::array<Vector3d, 2> tangents;
  interpolateSurface(nodes, shape, point, tangents, nullptr);
  return tangents[0].cross(tangents[1]).norm();
}

// Master segments facing the slave (clockwise in the plane, normal -n) a gap above it: a grid of
// cells of size h rotated by `angle`, the cells whose centre lies at u < `edge` (a free edge).
std::vector<NodeMatrix<double>> masterGrid(const TiltedPlane& plane, double h, double angle,
                                           double edge, double gap = 0.01) {
  const Eigen::Rotation2Dd rotation(angle);
  std::vector<NodeMatrix<double>> masters;
  for (int i = -6; i < 6; ++i) {
    for (int j = -6; j < 6; ++j) {
      const Vector2d centre = rotation * Vector2d((i + 0.5) * h, (j + 0.5) * h);
      if (centre[0] > edge) continue;
      std::array<Vector2d, 4> corners = {
          rotation * Vector2d(i * h, j * h), rotation * Vector2d(i * h, (j + 1) * h),
          rotation * Vector2d((i + 1) * h, (j + 1) * h), rotation * Vector2d((i + 1) * h, j * h)};
      masters.push_back(quad(plane, corners, gap));
    }
  }
  return masters;
}

struct Sums {
  double total = 0, covered = 0;
  std::size_t points = 0;
};

Sums integrateArea(const NodeMatrix<double>& slave, const std::vector<NodeMatrix<double>>& masters,
                   int rulePoints) {
  std::vector<Polygon2> images;
  for (const NodeMatrix<double>& m : masters) {
    // Far cells project beyond the extrapolation bound and have no image; a missed cell that
    // overlaps would show in the covered area.
    const std::optional<Polygon2> image = masterImage(shape::SurfaceType::Quad4, slave, m);
    if (image && overlapWithSquare(*image) > 0) images.push_back(*image);
  }
  Sums sums;
  for (const SegmentPoint& p : segmentPoints(images, rulePoints)) {
    EXPECT_LE(p.xi.cwiseAbs().maxCoeff(), 1 + 1e-14);
    const double dA = areaElement(slave, p.xi) * p.weight;
    sums.total += dA;
    if (p.image >= 0) sums.covered += dA;
    ++sums.points;
  }
  return sums;
}

TEST(SegmentPoints, WeightsSumToTheSlaveAreaWhateverTheOverlap) {
  const TiltedPlane plane;
  const NodeMatrix<double> slave = slaveQuad(plane);
  const double area = flatQuadArea(slave);
  // Non-matching rotated grids finer and coarser than the slave, covering it fully or partly.
  for (double h : {0.23, 0.41, 0.9}) {
    for (double angle : {0.0, 0.37}) {
      for (double edge : {5.0, 0.1}) {
        for (int rule : {1, 2, 3}) {
          SCOPED_TRACE(testing::Message()
                       << "h " << h << " angle " << angle << " edge " << edge << " rule " << rule);
          const Sums sums = integrateArea(slave, masterGrid(plane, h, angle, edge), rule);
          EXPECT_NEAR(sums.total / area, 1, 1e-13);
          EXPECT_GT(sums.points, 4u);  // every grid splits the slave
          if (edge > 1) {
            EXPECT_NEAR(sums.covered / area, 1, 1e-13);
          } else {
            EXPECT_LT(sums.covered / area, 1 - 1e-3);
          }
        }
      }
    }
  }
}

TEST(SegmentPoints, SlaveHalfOverTheMastersFreeEdgeGetsHalf) {
  // A rectangular slave [-0.5, 0.5] x [-0.5, 0.5]; the master ends at u = 0 (a free edge).
  const TiltedPlane plane;
  const NodeMatrix<double> slave = quad(
      plane, {Vector2d(-0.5, -0.5), Vector2d(0.5, -0.5), Vector2d(0.5, 0.5), Vector2d(-0.5, 0.5)});
  const std::vector<NodeMatrix<double>> masters = {
      quad(plane, {Vector2d(-1, -1), Vector2d(-1, 0.2), Vector2d(0, 0.2), Vector2d(0, -1)}, 0.01),
      quad(plane, {Vector2d(-1, 0.2), Vector2d(-1, 1), Vector2d(0, 1), Vector2d(0, 0.2)}, 0.01)};
  for (int rule : {1, 2, 3}) {
    const Sums sums = integrateArea(slave, masters, rule);
    EXPECT_NEAR(sums.total, 1.0, 1e-14);
    EXPECT_NEAR(sums.covered, 0.5, 1e-14);
  }
}

TEST(SegmentPoints, UnsplitSegmentKeepsTheGaussRule) {
  // One master segment covering the whole slave: the points are the Gauss points.
  const TiltedPlane plane;
  const NodeMatrix<double> slave = slaveQuad(plane);
  const NodeMatrix<double> master = quad(
      plane, {Vector2d(-1.2, -1.2), Vector2d(-1.2, 1.2), Vector2d(1.2, 1.2), Vector2d(1.2, -1.2)},
      0.01);
  const std::optional<Polygon2> image = masterImage(shape::SurfaceType::Quad4, slave, master);
  ASSERT_TRUE(image.has_value());
  const std::vector<SegmentPoint> points = segmentPoints({*image}, 2);
  const auto gauss = gaussQuad(2);
  ASSERT_EQ(points.size(), gauss.size());
  for (std::size_t k = 0; k < gauss.size(); ++k) {
    EXPECT_EQ(points[k].xi, gauss[k].xi);
    EXPECT_EQ(points[k].weight, gauss[k].weight);
    EXPECT_EQ(points[k].image, 0);
  }
}

TEST(SegmentPoints, TriangleRulesIntegrateTheirDegreeExactly) {
  // On a square split by two images, a polynomial of the rule's degree in xi is integrated
  // exactly: int over [-1,1]^2 of xi1^a xi2^b = 4/((a+1)(b+1)) for even a, b.
  const std::vector<Polygon2> images = {{{-3, -3}, {0.3, -3}, {0.1, 3}, {-3, 3}},
                                        {{0.3, -3}, {3, -3}, {3, 3}, {0.1, 3}}};
  const struct {
    int rule, a, b;
  } cases[] = {{1, 1, 0}, {2, 2, 0}, {2, 1, 1}, {3, 4, 0}, {3, 2, 2}, {3, 3, 2}};
  for (const auto& c : cases) {
    double sum = 0;
    for (const SegmentPoint& p : segmentPoints(images, c.rule)) {
      sum += p.weight * std::pow(p.xi[0], c.a) * std::pow(p.xi[1], c.b);
    }
    const double exact = (c.a % 2 || c.b % 2) ? 0.0 : 4.0 / ((c.a + 1) * (c.b + 1));
    EXPECT_NEAR(sum, exact, 1e-13) << c.rule << " " << c.a << " " << c.b;
  }
}

}  // namespace
}  // namespace cc::contact
