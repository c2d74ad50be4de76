// Master surface of a contact pair: its segments (Quad4/Quad9 faces), their edge neighbours,
// and the search for the segment a slave point projects onto: a local walk across edge
// neighbours from the point's current segment (points slide across any number of segments), and
// a global search through a bucket grid of segment bounding boxes, O(n) to build and O(1) per
// query, never an all-pairs loop.
#pragma once

#include <Eigen/Core>
#include <array>
#include <numbers>
#include <unordered_map>
#include <vector>

#include "contact/projection.hpp"
#include "mesh/mesh.hpp"

namespace cc::contact {

struct SegmentProjection {
  int segment = -1;  // -1: no segment found (the point projects outside the master surface)
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();
  double distance = 0;  // |r_s - rho|
  // The closest-point iteration broke down on a segment (ProjectionResult::brokeDown), so
  // "not found" may hide a point that is in contact.
  bool projectionBrokeDown = false;
  bool found() const { return segment >= 0; }
};

// The smoothing keeps an edge sharp where the facets turn by more than this (30 degrees): a
// curved surface meshed for contact turns by far less per facet (the ironing die 7 degrees, the
// committed ball decks at most 11), a tool's edge or a box corner (90) by far more. Deck:
// crease= (degrees).
constexpr double kDefaultCreaseAngle = 30.0 * std::numbers::pi / 180.0;
// A shared edge whose facets turn by more than this (1 degree) is a facet edge of a curved
// surface, not a round-off kink of a flat one.
constexpr double kTurningAngle = std::numbers::pi / 180.0;

class MasterSurface {
 public:
  MasterSurface() = default;
  explicit MasterSurface(const FaceSet& faces);

  shape::SurfaceType type() const { return type_; }
  int segmentCount() const { return static_cast<int>(segments_.rows()); }
  int nodesPerSegment() const { return static_cast<int>(segments_.cols()); }
  int node(int segment, int k) const { return segments_(segment, k); }
  // Neighbour across edge e (0: xi2 = -1, 1: xi1 = +1, 2: xi2 = +1, 3: xi1 = -1), or -1.
  int neighbour(int segment, int edge) const { return neighbours_[segment][edge]; }
  double freeEdgeReach() const;  // in parameter space, see master_surface.cpp
  NodeMatrix<double> segmentNodes(int segment, const Eigen::Matrix3Xd& coordinates) const;

  // Smoothed geometry (issue 16, part 2; Quad4 only): once switched on, projections use the
  // Nagata patch of nagata.hpp over the nodal normals of the last updateNormals().
  void setSmooth(bool smooth) { smooth_ = smooth; }
  bool smooth() const { return smooth_; }
  // Free edges where the contact force fades out (contact_point.hpp, kFreeEdgeBand).
  void setFadingEdges(bool fading) { fadingEdges_ = fading; }
  // Edges across which the facets turn by more than this angle (radians) are creases: kept
  // sharp by the smoothing (updateNormals).
  void setCreaseAngle(double radians) {
    creaseAngle_ = radians;
    creaseEdges_.clear();
  }
  double creaseAngle() const { return creaseAngle_; }
  // Which shared edges are creases, from `reference` (the mesh as given), kept until the crease
  // angle changes. updateNormals finds them on its own coordinates if this was not called.
  void findCreases(const Eigen::Matrix3Xd& reference);
  int creaseCount() const;
  // How the facets turn across the shared edges of the mesh as given: a faceted master whose
  // edges mostly turn by a few degrees is a curved surface cut into facets (run_command.cpp says
  // so, since points crossing those edges slow Newton down: docs/verification/sliding.md).
  struct FacetTurns {
    int sharedEdges = 0;
    int turning = 0;     // shared edges turning by more than kTurningAngle, up to the crease angle
    double largest = 0;  // radians, over those
  };
  FacetTurns facetTurns(const Eigen::Matrix3Xd& reference) const;
  // Nodal normals of the surface at `coordinates`: at each node the average of the adjacent
  // segments' corner normals weighted by their corner angles (Thuermer & Wuethrich 1998; on a
  // mesh symmetric about the node, e.g. a uniform one on a cylinder, the exact normal up to
  // O(h^2)), taken separately on each side of a crease; crease edges stay straight.
  void updateNormals(const Eigen::Matrix3Xd& coordinates);
  // Whether edge e of `segment` is a crease (after updateNormals).
  bool crease(int segment, int edge) const { return creaseEdges_[segment][edge]; }
  NodalNormals segmentNormals(int segment) const;

  // Rebuilds the bucket grid for the current coordinates (once per step or when points get
  // lost); segment boxes grow by `reachInSegments` times the mean segment size (expected
  // maximum gap + slip per step). Relative to the segments, so that a cell holds a bounded
  // number of them however fine the mesh: the search stays O(1) per point.
  void buildSearchGrid(const Eigen::Matrix3Xd& coordinates, double reachInSegments);

  // Local search: project on `start`, walk to edge neighbours while the parameter leaves the
  // segment. Returns a segment only if the point projects inside one. A point that has `hopped`
  // back and forth over an edge in this step keeps `start` while it leaves by up to
  // kHopStayTolerance (master_surface.cpp).
  SegmentProjection walk(int start, const Eigen::Vector2d& guess, const Eigen::Vector3d& point,
                         const Eigen::Matrix3Xd& coordinates, bool hopped = false) const;
  // Global search through the grid (needs buildSearchGrid): the closest inside projection.
  SegmentProjection search(const Eigen::Vector3d& point, const Eigen::Matrix3Xd& coordinates) const;

 private:
  struct SharedEdge {
    int other = -1;                      // the neighbouring segment
    int otherStart = -1, otherEnd = -1;  // its corners at the edge's start and end
  };
  SharedEdge sharedEdge(int s, int e) const;
  double turnAcross(int s, int e, const std::vector<Eigen::Vector3d>& unit) const;
  void cornerNormalsOf(const Eigen::Matrix3Xd& coordinates, std::vector<Eigen::Vector3d>& weighted,
                       std::vector<Eigen::Vector3d>& unit) const;
  // Whether a projection parameter lies on the segment (up to `tolerance` beyond a shared edge),
  // or just beyond a free surface edge.
  bool accepts(int segment, const Eigen::Vector2d& xi, double tolerance) const;

  using CellKey = long long;
  CellKey cellKey(const Eigen::Vector3i& cell) const;
  Eigen::Vector3i cellOf(const Eigen::Vector3d& point) const;

  // The projection of `point` on `segment` (smoothed when switched on).
  ProjectionResult projectOn(int segment, const Eigen::Vector3d& point,
                             const Eigen::Vector2d& guess,
                             const Eigen::Matrix3Xd& coordinates) const;
  // A lower bound of the distance from `point` to an accepted projection on `segment`.
  double distanceBound(int segment, const Eigen::Vector3d& point,
                       const Eigen::Matrix3Xd& coordinates) const;
  // Whether `point` lies beyond distanceBound of `segment` on its open side (no contact).
  bool apartFrom(int segment, const Eigen::Vector3d& point,
                 const Eigen::Matrix3Xd& coordinates) const;
  // Distance from `point` to the segment's point at xi.
  double distanceTo(int segment, const Eigen::Vector2d& xi, const Eigen::Vector3d& point,
                    const Eigen::Matrix3Xd& coordinates) const;

  shape::SurfaceType type_ = shape::SurfaceType::Quad4;
  bool smooth_ = false;
  bool fadingEdges_ = false;
  double creaseAngle_ = kDefaultCreaseAngle;
  // Per segment corner, the normal of its fan (the node's normal unless the node is on a crease).
  std::vector<std::array<Eigen::Vector3d, 4>> cornerNormals_;
  std::vector<std::array<bool, 4>> creaseEdges_;  // per segment edge
  // Per segment edge, the tangential term of Nagata's c (nagata.hpp) from updateNormals().
  std::vector<std::array<Eigen::Vector3d, 4>> fixedCorrections_;
  Connectivity segments_;
  std::vector<std::array<int, 4>> neighbours_;
  double typicalSize_ = 1;
  // Bucket grid: segment indices per cell of size cellSize_ (hashed, sparse).
  double cellSize_ = 1;
  Eigen::Vector3d gridOrigin_ = Eigen::Vector3d::Zero();
  std::unordered_map<CellKey, std::vector<int>> cells_;
};

}  // namespace cc::contact
