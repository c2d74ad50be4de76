// Search tracking of a contact pair: keeps every NTS/STS point on the master segment it projects
// onto, by a local walk across edge neighbours from the point's current segment and the global
// grid search for points that lost theirs; the grid is rebuilt once per step attempt.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "contact/contact_points.hpp"
#include "contact/master_surface.hpp"
#include "fem/contribution.hpp"

namespace cc::contact {

class SegmentTracker {
 public:
  SegmentTracker() = default;
  explicit SegmentTracker(const FaceSet& master) : master_(master) {}

  const MasterSurface& master() const { return master_; }
  // Smoothed master (nagata.hpp): switch on, and the nodal normals for a step.
  void setSmooth(bool smooth) { master_.setSmooth(smooth); }
  void setCreaseAngle(double radians) { master_.setCreaseAngle(radians); }
  void findCreases(const Eigen::Matrix3Xd& reference) { master_.findCreases(reference); }
  void setFadingEdges(bool fading) { master_.setFadingEdges(fading); }
  void updateNormals(const Eigen::Matrix3Xd& x) { master_.updateNormals(x); }

  // Assigns every point its master segment and parameter at the coordinates x; `moved` receives
  // the indices of the points whose segment changed. Fails with ProjectionFailure when a point's
  // projection broke down on its own segment and no other segment holds it: treating it as open
  // could drop a point that is in contact.
  LocalStatus track(std::vector<PairPoint>& points, const Eigen::Matrix3Xd& x, double time,
                    const std::string& pairName, std::vector<int>& moved);

  // Builds the search grid for the coordinates x at `time` unless it is built for that time.
  void buildGrid(const Eigen::Matrix3Xd& x, double time);

  // The master moved without a new time (a cut-back retries the same time): rebuild the grid.
  void invalidateGrid() { gridTime_ = -1; }

 private:
  MasterSurface master_;
  double gridTime_ = -1;  // time of the coordinates the search grid was built for
};

}  // namespace cc::contact
