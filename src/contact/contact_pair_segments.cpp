// integration=segments of an STS pair (issue 16, part 1): the points are rebuilt once per step
// from the converged configuration at its start (segmentation.hpp) and carry the history over.
//
// Why once per step and not per iteration: points that move with the iterate would make the
// residual non-smooth wherever a piece appears or vanishes and the tangent would miss the
// points' motion; fixed points keep Newton's quadratic tail, the paper's tangent parts and the
// exact tangent unchanged (the choice of most mortar codes). The price: within a step a point
// can still slide across a master edge; the error is of the order of the step's slip over the
// segment size instead of the whole segment.

#include <limits>

#include "contact/contact_pair.hpp"

namespace cc::contact {

LocalStatus ContactPair::resegment(const AssemblyState& state) {
  const Eigen::Matrix3Xd& x = *state.previous;
  tracker_.buildGrid(x, state.previousTime);
  std::vector<PairPoint> fresh =
      segmentedSegmentToSegmentPoints(slaveFaces_, master(), x, config_.integrationPoints);
  if (historyInitialized_) {
    // The nearest old point on the same slave segment (slave parameter plane) hands over its
    // history and is where the search walk of the new point starts.
    std::vector<std::vector<int>> onFace(static_cast<std::size_t>(slaveFaces_.connectivity.rows()));
    for (std::size_t i = 0; i < points_.size(); ++i) {
      onFace[static_cast<std::size_t>(points_[i].slaveFace)].push_back(static_cast<int>(i));
    }
    for (PairPoint& p : fresh) {
      const PairPoint* nearest = nullptr;
      double best = std::numeric_limits<double>::infinity();
      for (int i : onFace[static_cast<std::size_t>(p.slaveFace)]) {
        const double d = (points_[i].slave.gaussPoint - p.slave.gaussPoint).squaredNorm();
        if (d < best) best = d, nearest = &points_[i];
      }
      if (!nearest) continue;
      p.committed = nearest->committed;
      p.multiplierNormal = nearest->multiplierNormal;
      p.committedMultiplierNormal = nearest->committedMultiplierNormal;
      p.tractionAugmentation = nearest->tractionAugmentation;
      p.segment = nearest->committedSearchSegment;
      p.xi = nearest->committedSearchXi;
    }
    const LocalStatus status = tracker_.track(fresh, x, state.previousTime, config_.name, moved_);
    if (!status.ok) return status;
    for (PairPoint& p : fresh) inheritHistory(p, x);
  }
  points_ = std::move(fresh);
  for (PairPoint& p : points_) buildItem(p);
  countedState_.clear();  // the per-point diagnostics start over with the new indices
  countedSegment_.clear();
  ++topologyVersion_;
  segmentsTime_ = state.previousTime;
  segmentsReady_ = true;
  return LocalStatus::success();
}

// The converged projection of the new point (Table 1, step 1, at the step's start) replaces the
// old point's, so that the slip of eq. (47) starts from the new point's own master point; the
// old point's traction T^(n) is kept, in the tangent plane at the new projection with its
// covariant components T_i = T . rho_i there (for the convective update).
void ContactPair::inheritHistory(PairPoint& point, const Eigen::Matrix3Xd& x) const {
  PointHistory& h = point.committed;
  h.projected = point.segment >= 0;
  h.segment = point.segment;
  h.xi = point.xi;
  point.committedSearchSegment = point.segment;
  point.committedSearchXi = point.xi;
  point.segmentChangesInStep = 0;
  if (!h.projected || h.state == ContactState::Open) {
    h.traction.setZero();
    h.tractionCovariant.setZero();
    if (!h.projected) h.state = ContactState::Open;
    return;
  }
  const NodalNormals normals =
      config_.smoothMaster ? master().segmentNormals(point.segment) : NodalNormals{};
  const SurfaceFrame<double> frame =
      surfaceFrame(master().type(), master().segmentNodes(point.segment, x), point.xi[0],
                   point.xi[1], config_.smoothMaster ? &normals : nullptr);
  h.traction -= h.traction.dot(frame.normal) * frame.normal;
  for (int i = 0; i < 2; ++i) h.tractionCovariant[i] = h.traction.dot(frame.rhoCov[i]);
}

}  // namespace cc::contact
