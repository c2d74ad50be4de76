// Search on a master surface with a ridge (a convex kink seen from the slave side): a slave point
// under the shared edge projects beyond that edge on both segments, yet it is in contact there.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_pair.hpp"
#include "contact/master_surface.hpp"

namespace cc::contact {
namespace {

using Eigen::Vector3d;

// Two Quad4 segments over x in [0, 2], y in [0, 1], normal +z, forming the V z = slope |x - 1|:
// seen from below (the penetration side, g < 0) the shared edge x = 1 is a ridge.
struct Ridge {
  Eigen::Matrix3Xd coordinates;
  FaceSet faces;
};

Ridge makeRidge(double slope) {
  Ridge r;
  r.coordinates.resize(3, 6);
  for (int j = 0; j <= 1; ++j) {
    for (int i = 0; i <= 2; ++i)
      r.coordinates.col(3 * j + i) = Vector3d(i, j, slope * std::abs(i - 1.0));
  }
  r.faces.type = CellType::Quad4;
  r.faces.connectivity.resize(2, 4);
  r.faces.connectivity.row(0) << 0, 1, 4, 3;
  r.faces.connectivity.row(1) << 1, 2, 5, 4;
  return r;
}

// The foot of the perpendicular from (1, y, -depth) on the left segment's plane lies beyond the
// edge by 2 depth slope / (1 + slope^2) in its parameter, at distance depth / sqrt(1 + slope^2).
double excessBeyondEdge(double depth, double slope) {
  return 2 * depth * slope / (1 + slope * slope);
}
double distanceToPlane(double depth, double slope) {
  return depth / std::sqrt(1 + slope * slope);
}

TEST(MasterSurfaceRidge, PointUnderRidgeStaysOnItsSegment) {
  const double slope = 0.01, depth = 1e-3;
  const Ridge ridge = makeRidge(slope);
  MasterSurface master(ridge.faces);
  const Vector3d point(1, 0.5, -depth);
  // The case this test is about: beyond the edge on both segments, by far more than round-off.
  const ProjectionResult onLeft =
      closestPointProjection(shape::SurfaceType::Quad4, master.segmentNodes(0, ridge.coordinates),
                             point, Eigen::Vector2d::Zero());
  ASSERT_TRUE(onLeft.converged);
  EXPECT_NEAR(onLeft.xi[0] - 1, excessBeyondEdge(depth, slope), 1e-12);
  for (int start : {0, 1}) {
    const SegmentProjection found =
        master.walk(start, Eigen::Vector2d::Zero(), point, ridge.coordinates);
    ASSERT_TRUE(found.found()) << "walk from segment " << start;
    EXPECT_EQ(found.segment, start);  // no hand-over between Newton iterations
    EXPECT_NEAR(std::abs(found.xi[0]) - 1, excessBeyondEdge(depth, slope), 1e-12);
    EXPECT_NEAR(found.distance, distanceToPlane(depth, slope), 1e-15);
  }
  // Where the ridge meets the master's free edge y = 0, a point slightly beyond that edge (within
  // its tolerance) is in contact too.
  const Vector3d atBoundary(1, -1e-4, -depth);
  for (int start : {0, 1}) {
    const SegmentProjection found =
        master.walk(start, Eigen::Vector2d::Zero(), atBoundary, ridge.coordinates);
    ASSERT_TRUE(found.found()) << "walk from segment " << start << " at the free edge";
    EXPECT_EQ(found.segment, start);
    EXPECT_NEAR(found.distance, distanceToPlane(depth, slope), 1e-15);
  }
  master.buildSearchGrid(ridge.coordinates, 1.0);
  const SegmentProjection searched = master.search(point, ridge.coordinates);
  ASSERT_TRUE(searched.found());
  EXPECT_NEAR(searched.distance, distanceToPlane(depth, slope), 1e-15);
}

TEST(MasterSurfaceRidge, FarBeyondEdgesNothingIsFound) {
  // A 90-degree ridge and a point 0.5 below it: 0.5 beyond the edge in parameter, far more than
  // the extrapolation allowed for a ridge.
  const double slope = 1, depth = 0.5;
  const Ridge ridge = makeRidge(slope);
  MasterSurface master(ridge.faces);
  EXPECT_FALSE(
      master.walk(0, Eigen::Vector2d::Zero(), Vector3d(1, 0.5, -depth), ridge.coordinates).found());
  // Beyond the free edge x = 0 (no neighbour) by 0.1: outside the master surface.
  const Ridge flat = makeRidge(0);
  MasterSurface flatMaster(flat.faces);
  EXPECT_FALSE(
      flatMaster.walk(0, Eigen::Vector2d::Zero(), Vector3d(-0.1, 0.5, -1e-3), flat.coordinates)
          .found());
}

// NTS: slave nodes under the ridge are in contact with the gap to the segment's plane, in the
// first evaluation and in every later one (before, they were declared open).
TEST(MasterSurfaceRidge, SlaveNodesUnderRidgeAreInContact) {
  const double slope = 0.01, depth = 1e-3;
  const Ridge ridge = makeRidge(slope);
  Mesh mesh;
  mesh.coordinates.resize(3, 10);
  mesh.coordinates.leftCols(6) = ridge.coordinates;
  // Slave face from x = 1 (under the ridge) to x = 3 (beyond the master: open), normal -z.
  mesh.coordinates.rightCols(4) << 1, 1, 3, 3, 0, 1, 1, 0, -depth, -depth, -depth, -depth;
  FaceSet slave;
  slave.type = CellType::Quad4;
  slave.connectivity.resize(1, 4);
  slave.connectivity.row(0) << 6, 7, 8, 9;
  ContactPairConfig config;
  config.name = "ridge";
  config.kind = PointKind::NodeToSegment;
  config.law = {1.0e3, 1.0e3, 0.0};
  auto pair = ContactPair::nodeToSegment(config, mesh, ridge.faces, slave);
  const Eigen::Matrix3Xd& x = mesh.coordinates;
  for (int iteration = 0; iteration < 2; ++iteration) {
    AssemblyState state{1, 0, &x, &x, &x};
    ASSERT_TRUE(pair->prepare(state).ok);
    for (std::size_t i = 0; i < pair->itemCount(); ++i) {
      Eigen::VectorXd force = Eigen::VectorXd::Zero(3 * pair->itemNodes(i).size());
      ASSERT_TRUE(pair->evaluate(i, state, force, nullptr).ok);
    }
    const ContactPairRecord record = pair->record();
    int inContact = 0;
    for (int i = 0; i < record.gap.size(); ++i) {
      if (std::abs(record.position(0, i) - 1) > 1e-12) continue;
      EXPECT_NEAR(record.gap[i], -distanceToPlane(depth, slope), 1e-15);
      EXPECT_NEAR(record.normalTraction[i], -1.0e3 * distanceToPlane(depth, slope), 1e-12);
      ++inContact;
    }
    EXPECT_EQ(inContact, 2);
  }
}

}  // namespace
}  // namespace cc::contact
