// STS points of integration=segments: per slave segment, the master segments it overlaps (found
// from the segments under a few of its points and grown across edge neighbours while they
// overlap), their images in its parameter plane, and the points of segmentation.hpp on them.
#include <algorithm>
#include <deque>
#include <set>

#include "contact/contact_points.hpp"
#include "contact/segmentation.hpp"

namespace cc::contact {

namespace {

// Master segments examined per slave segment at most: a slave segment overlaps a handful; the
// bound only stops a runaway growth on a degenerate configuration.
constexpr std::size_t kMaxCandidates = 256;

NodeMatrix<double> nodesOf(const FaceSet& faces, int face, const Eigen::Matrix3Xd& x) {
  NodeMatrix<double> nodes(3, faces.connectivity.cols());
  for (int k = 0; k < nodes.cols(); ++k) nodes.col(k) = x.col(faces.connectivity(face, k));
  return nodes;
}

NodeMatrix<double> cornersOf(const MasterSurface& master, int segment, const Eigen::Matrix3Xd& x) {
  NodeMatrix<double> corners(3, 4);
  for (int k = 0; k < 4; ++k) corners.col(k) = x.col(master.node(segment, k));
  return corners;
}

// The images of the master segments overlapping the slave segment, in a deterministic order
// (breadth first from the seeds in ascending order, neighbours in edge order).
std::vector<Polygon2> overlappingImages(const MasterSurface& master, shape::SurfaceType type,
                                        const NodeMatrix<double>& slaveNodes,
                                        const Eigen::Matrix3Xd& x) {
  std::set<int> seeds;
  for (double s : {-1.0, 0.0, 1.0}) {
    for (double t : {-1.0, 0.0, 1.0}) {
      const shape::SurfaceShape<double> shape = shape::surfaceShape(type, s, t);
      Eigen::Vector3d position = Eigen::Vector3d::Zero();
      for (int k = 0; k < shape.count; ++k) position += shape.value[k] * slaveNodes.col(k);
      const SegmentProjection found = master.search(position, x);
      if (found.found()) seeds.insert(found.segment);
    }
  }
  std::deque<int> queue(seeds.begin(), seeds.end());
  std::set<int> visited(seeds.begin(), seeds.end());
  std::vector<Polygon2> images;
  while (!queue.empty() && visited.size() <= kMaxCandidates) {
    const int segment = queue.front();
    queue.pop_front();
    const std::optional<Polygon2> image =
        masterImage(type, slaveNodes, cornersOf(master, segment, x));
    if (!image || overlapWithSquare(*image) <= 0) continue;
    images.push_back(*image);
    for (int edge = 0; edge < 4; ++edge) {
      const int next = master.neighbour(segment, edge);
      if (next >= 0 && visited.insert(next).second) queue.push_back(next);
    }
  }
  return images;
}

}  // namespace

std::vector<PairPoint> segmentedSegmentToSegmentPoints(const FaceSet& slave,
                                                       const MasterSurface& master,
                                                       const Eigen::Matrix3Xd& x,
                                                       int integrationPoints) {
  std::vector<PairPoint> points;
  const shape::SurfaceType type =
      slave.type == CellType::Quad9 ? shape::SurfaceType::Quad9 : shape::SurfaceType::Quad4;
  for (int face = 0; face < slave.connectivity.rows(); ++face) {
    const NodeMatrix<double> slaveNodes = nodesOf(slave, face, x);
    const std::vector<Polygon2> images = overlappingImages(master, type, slaveNodes, x);
    for (const SegmentPoint& q : segmentPoints(images, integrationPoints)) {
      points.push_back(slaveSegmentPoint(slave, face, q.xi, q.weight));
    }
  }
  return points;
}

}  // namespace cc::contact
