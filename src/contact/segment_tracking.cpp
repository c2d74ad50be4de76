// Search tracking: local walk from each point's segment, global grid search as the fallback.
#include "contact/segment_tracking.hpp"

#include <fmt/format.h>

namespace cc::contact {

namespace {

// Reach of the global search, in master segment sizes: a point that lost its segment is within
// one segment of its new one (gap and slip of a step are smaller than a segment). Before this
// was relative, the first search used a reach of one length unit, which on a fine mesh put
// hundreds of segments in every grid cell (issue 8).
constexpr double kSearchReachInSegments = 1.0;

}  // namespace

void SegmentTracker::buildGrid(const Eigen::Matrix3Xd& x, double time) {
  if (gridTime_ != time) {
    master_.buildSearchGrid(x, kSearchReachInSegments);
    gridTime_ = time;
  }
}

LocalStatus SegmentTracker::track(std::vector<PairPoint>& points, const Eigen::Matrix3Xd& x,
                                  double time, const std::string& pairName,
                                  std::vector<int>& moved) {
  moved.clear();
  buildGrid(x, time);
  for (std::size_t i = 0; i < points.size(); ++i) {
    PairPoint& point = points[i];
    const Eigen::Vector3d position = slavePosition(point, x);
    SegmentProjection found;
    if (point.segment >= 0) {
      found = master_.walk(point.segment, point.xi, position, x, point.hopped());
    }
    const bool brokeDownOnOwnSegment = found.projectionBrokeDown;
    if (!found.found()) found = master_.search(position, x);
    if (!found.found() && brokeDownOnOwnSegment) {
      return LocalStatus::failure(
          FailureKind::ProjectionFailure,
          fmt::format("contact pair '{}': the closest-point projection of slave point {} onto "
                      "master segment {} broke down (degenerate or strongly distorted segment)",
                      pairName, i, point.segment));
    }
    if (found.segment != point.segment) {
      point.segment = found.segment;
      ++point.segmentChangesInStep;
      moved.push_back(static_cast<int>(i));
    }
    point.xi = found.xi;
  }
  return LocalStatus::success();
}

}  // namespace cc::contact
