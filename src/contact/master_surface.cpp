// Master surface: segment adjacency, bucket-grid global search, local walk across neighbours.
#include "contact/master_surface.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "contact/contact_point.hpp"

namespace cc::contact {

namespace {

// Number of edge-neighbour hops a local walk may take before falling back to the global search.
constexpr int kMaxWalkHops = 64;
// Parameter tolerance for "inside the segment": points on an edge or vertex belong to both.
constexpr double kInsideTolerance = 1e-10;
// A point keeps the segment it is on while its projection leaves it across a shared edge by at
// most this much in parameter space. Without this hysteresis a slave point lying exactly on an
// edge where the master surface has a (round-off or deformation) kink is handed back and forth
// between the two segments in successive Newton iterations, and the tilt of their normals makes
// the residual oscillate at about 1e-7 of its first value forever (input/stress/
// slave_on_master_edges_sts.deck). Both segments are correct within the kink's angle there.
constexpr double kStayOnSegmentTolerance = 1e-6;
// A point that has already changed segment twice in a step (over there and back) keeps its
// segment while its projection leaves it by up to this much. Where the master's normal jumps
// at an edge (a faceted master, or a Nagata patch edge: C0 in the normal) an NTS node that
// presses on the edge has no equilibrium on either segment: on each, its force pushes it over
// the edge onto the other, by ~1e-5 in parameter space, and Newton alternates between the two
// at a relative residual of ~1e-10 for ever (the smoothed ironing die with the energy
// criterion: 3 points every iteration, relative energy 1.5e-16 against 1e-16, a cut-back in
// most sliding steps). Held, the point converges slightly beyond the edge: its segment's
// surface extended by at most 1e-3 of the parameter range, which on a facet of kink angle a
// moves the contact point by at most 1e-3 a of half a segment.
constexpr double kHopStayTolerance = 1e-3;
// Above a ridge of the master surface (segments meeting at a convex kink seen from the slave
// side, e.g. where a concentrated slave-node force dents a C0 Quad9 surface at an element edge)
// lies a wedge from which a point projects beyond the shared edge on each segment: its closest
// point is on the ridge itself. Such a point is in contact with the segments there, and the
// (slightly extrapolated) projection on one of them stands in for the ridge point to first order.
// Without this, a penetrating slave node above such an edge was declared open, the dent relaxed,
// the node was found again and Newton alternated between the two states forever
// (parabolic_block_6_2a with the base offset by half an element). The bound, the same 1% of the
// half segment as beyond a free edge, keeps the extrapolation short.
constexpr double kRidgeTolerance = kFreeEdgeTolerance;

// Smoothed master: a projection is refined on the Nagata patch only if the faceted one lies
// within this distance of the segment in parameter space (see projectOn).
constexpr double kSmoothRefineReach = 0.5;

// Corners of edge e in the Quad4/Quad9 numbering: (0,1), (1,2), (2,3), (3,0).
std::pair<int, int> edgeCorners(int edge) {
  return {edge, (edge + 1) % 4};
}

// The edges the parameter leaves through, most violated first.
std::vector<int> violatedEdges(const Eigen::Vector2d& xi) {
  std::vector<std::pair<double, int>> violations;
  if (xi[1] < -1) violations.push_back({-1 - xi[1], 0});
  if (xi[0] > 1) violations.push_back({xi[0] - 1, 1});
  if (xi[1] > 1) violations.push_back({xi[1] - 1, 2});
  if (xi[0] < -1) violations.push_back({-1 - xi[0], 3});
  std::sort(violations.rbegin(), violations.rend());
  std::vector<int> edges;
  for (const auto& v : violations) edges.push_back(v.second);
  return edges;
}

// How far the parameter lies beyond edge e (negative: inside).
double edgeExcess(const Eigen::Vector2d& xi, int edge) {
  return edge == 0 ? -1 - xi[1] : edge == 1 ? xi[0] - 1 : edge == 2 ? xi[1] - 1 : -1 - xi[0];
}

// How far the parameter lies beyond the segment, over all four edges (0 inside).
double largestExcess(const Eigen::Vector2d& xi) {
  return std::max(0.0, xi.cwiseAbs().maxCoeff() - 1);
}

}  // namespace

// Beyond a free edge of the master surface (an edge without a neighbour) a projection still
// counts up to this distance in parameter space: full force up to kFreeEdgeTolerance; with
// edge=fade a force falling smoothly to zero beyond (contact_point.hpp, freeEdgeFactor).
double MasterSurface::freeEdgeReach() const {
  return fadingEdges_ ? kFreeEdgeTolerance + kFreeEdgeBand : kFreeEdgeTolerance;
}

bool MasterSurface::accepts(int segment, const Eigen::Vector2d& xi, double tolerance) const {
  for (int edge : violatedEdges(xi)) {
    const double excess = edgeExcess(xi, edge);
    if (excess <= tolerance) continue;
    if (neighbour(segment, edge) >= 0 || excess > freeEdgeReach()) return false;
  }
  return true;
}

MasterSurface::MasterSurface(const FaceSet& faces)
    : type_(faces.type == CellType::Quad9 ? shape::SurfaceType::Quad9 : shape::SurfaceType::Quad4),
      segments_(faces.connectivity),
      neighbours_(faces.connectivity.rows(), std::array<int, 4>{-1, -1, -1, -1}) {
  std::map<std::pair<int, int>, std::pair<int, int>> edgeOwner;  // sorted corners -> (seg, edge)
  for (int s = 0; s < segmentCount(); ++s) {
    for (int e = 0; e < 4; ++e) {
      auto [a, b] = edgeCorners(e);
      std::pair<int, int> key = std::minmax(segments_(s, a), segments_(s, b));
      auto [it, inserted] = edgeOwner.emplace(key, std::make_pair(s, e));
      if (!inserted) {
        neighbours_[s][e] = it->second.first;
        neighbours_[it->second.first][it->second.second] = s;
      }
    }
  }
}

NodeMatrix<double> MasterSurface::segmentNodes(int segment,
                                               const Eigen::Matrix3Xd& coordinates) const {
  NodeMatrix<double> nodes(3, nodesPerSegment());
  for (int k = 0; k < nodesPerSegment(); ++k) nodes.col(k) = coordinates.col(segments_(segment, k));
  return nodes;
}

namespace {

// Union-find over segment corners (4 s + k), for the smooth fans around each node.
int fanRoot(std::vector<int>& parent, int corner) {
  while (parent[corner] != corner) corner = parent[corner] = parent[parent[corner]];
  return corner;
}

// The corner of `segment` at mesh node `node` (-1 if none).
int cornerAt(const Connectivity& segments, int segment, int node) {
  for (int k = 0; k < 4; ++k) {
    if (segments(segment, k) == node) return k;
  }
  return -1;
}

}  // namespace

// Angle-weighted corner normals of the facets (Thuermer & Wuethrich) and their unit vectors,
// per segment corner 4 s + k.
void MasterSurface::cornerNormalsOf(const Eigen::Matrix3Xd& coordinates,
                                    std::vector<Eigen::Vector3d>& weighted,
                                    std::vector<Eigen::Vector3d>& unit) const {
  weighted.assign(4 * segmentCount(), Eigen::Vector3d::Zero());
  unit.assign(4 * segmentCount(), Eigen::Vector3d::Zero());
  for (int s = 0; s < segmentCount(); ++s) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d corner = coordinates.col(segments_(s, k));
      const Eigen::Vector3d next = coordinates.col(segments_(s, (k + 1) % 4)) - corner;
      const Eigen::Vector3d previous = coordinates.col(segments_(s, (k + 3) % 4)) - corner;
      const Eigen::Vector3d cross = next.cross(previous);  // along rho_1 x rho_2 at the corner
      const double angle = std::atan2(cross.norm(), next.dot(previous));
      if (cross.norm() > 0) {
        unit[4 * s + k] = cross.normalized();
        weighted[4 * s + k] = angle * unit[4 * s + k];
      }
    }
  }
}

// Edge e of segment s seen once per pair (from the lower segment): the neighbour t > s and its
// corners at the edge's start and end; t = -1 for a free edge or the other side of a pair.
MasterSurface::SharedEdge MasterSurface::sharedEdge(int s, int e) const {
  const int t = neighbour(s, e);
  if (t < s) return {};
  const int ti = cornerAt(segments_, t, segments_(s, nagataEdgeStart(e)));
  const int tj = cornerAt(segments_, t, segments_(s, nagataEdgeEnd(e)));
  if (ti < 0 || tj < 0) return {};
  return {t, ti, tj};
}

// The angle by which the facets turn across edge e of segment s (shared with t > s), from the
// corner normals `unit` of cornerNormalsOf; negative if the edge is free or seen from t's side.
double MasterSurface::turnAcross(int s, int e, const std::vector<Eigen::Vector3d>& unit) const {
  const SharedEdge edge = sharedEdge(s, e);
  if (edge.other < 0) return -1;
  const Eigen::Vector3d mine = unit[4 * s + nagataEdgeStart(e)] + unit[4 * s + nagataEdgeEnd(e)];
  const Eigen::Vector3d theirs =
      unit[4 * edge.other + edge.otherStart] + unit[4 * edge.other + edge.otherEnd];
  return std::atan2(mine.cross(theirs).norm(), mine.dot(theirs));
}

// A shared edge across which the facets turn by more than the crease angle stays sharp. Decided
// once, on the mesh as given (a tool's edges are a property of its design, and a decision
// repeated on the deformed surface would flip edges near the angle from step to step).
void MasterSurface::findCreases(const Eigen::Matrix3Xd& reference) {
  std::vector<Eigen::Vector3d> weighted, unit;
  cornerNormalsOf(reference, weighted, unit);
  creaseEdges_.assign(segmentCount(), {false, false, false, false});
  for (int s = 0; s < segmentCount(); ++s) {
    for (int e = 0; e < 4; ++e) {
      if (turnAcross(s, e, unit) <= creaseAngle_) continue;
      const int t = neighbour(s, e);
      creaseEdges_[s][e] = true;
      for (int f = 0; f < 4; ++f) {
        if (neighbour(t, f) == s) creaseEdges_[t][f] = true;
      }
    }
  }
}

MasterSurface::FacetTurns MasterSurface::facetTurns(const Eigen::Matrix3Xd& reference) const {
  std::vector<Eigen::Vector3d> weighted, unit;
  cornerNormalsOf(reference, weighted, unit);
  FacetTurns turns;
  for (int s = 0; s < segmentCount(); ++s) {
    for (int e = 0; e < 4; ++e) {
      const double turn = turnAcross(s, e, unit);
      if (turn < 0) continue;
      ++turns.sharedEdges;
      if (turn > kTurningAngle && turn <= creaseAngle_) {
        ++turns.turning;
        turns.largest = std::max(turns.largest, turn);
      }
    }
  }
  return turns;
}

int MasterSurface::creaseCount() const {
  int count = 0;
  for (const auto& edges : creaseEdges_)
    count += static_cast<int>(std::count(edges.begin(), edges.end(), true));
  return count / 2;  // each from both sides
}

void MasterSurface::updateNormals(const Eigen::Matrix3Xd& coordinates) {
  if (static_cast<int>(creaseEdges_.size()) != segmentCount()) findCreases(coordinates);
  const int corners = 4 * segmentCount();
  std::vector<Eigen::Vector3d> weighted, unit;
  cornerNormalsOf(coordinates, weighted, unit);
  // Fans: the corners around a node joined through the shared edges that are not creases; each
  // fan gets its own normal, so a node on a crease has one normal per side.
  std::vector<int> parent(corners);
  for (int c = 0; c < corners; ++c) parent[c] = c;
  for (int s = 0; s < segmentCount(); ++s) {
    for (int e = 0; e < 4; ++e) {
      const SharedEdge edge = sharedEdge(s, e);
      if (edge.other < 0 || creaseEdges_[s][e]) continue;
      parent[fanRoot(parent, 4 * s + nagataEdgeStart(e))] =
          fanRoot(parent, 4 * edge.other + edge.otherStart);
      parent[fanRoot(parent, 4 * s + nagataEdgeEnd(e))] =
          fanRoot(parent, 4 * edge.other + edge.otherEnd);
    }
  }
  // Each fan's normal, summed in segment order (without creases: the node's average as before).
  std::vector<Eigen::Vector3d> fan(corners, Eigen::Vector3d::Zero());
  for (int c = 0; c < corners; ++c) fan[fanRoot(parent, c)] += weighted[c];
  cornerNormals_.resize(segmentCount());
  for (int s = 0; s < segmentCount(); ++s) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d& sum = fan[fanRoot(parent, 4 * s + k)];
      cornerNormals_[s][k] = sum.norm() > 0 ? Eigen::Vector3d(sum / sum.norm()) : sum;
    }
  }
  // Per edge, from the same configuration and held fixed over the step with the normals (as a
  // vector, see nagataFixedTangentialTerm): shared edges get the same term from both sides (with
  // the edge's direction reversed, the chord, dv and the term all change sign).
  fixedCorrections_.resize(segmentCount());
  for (int s = 0; s < segmentCount(); ++s) {
    for (int e = 0; e < 4; ++e) {
      const int i = segments_(s, nagataEdgeStart(e)), j = segments_(s, nagataEdgeEnd(e));
      fixedCorrections_[s][e] =
          creaseEdges_[s][e] ? Eigen::Vector3d::Zero()
                             : nagataFixedTangentialTerm(cornerNormals_[s][nagataEdgeStart(e)],
                                                         cornerNormals_[s][nagataEdgeEnd(e)],
                                                         coordinates.col(j) - coordinates.col(i));
    }
  }
}

NodalNormals MasterSurface::segmentNormals(int segment) const {
  NodalNormals normals;
  for (int k = 0; k < 4; ++k) normals[k] = cornerNormals_[segment][k];
  normals.tangentialScale = {0, 0, 0, 0};  // the second term is in fixedCorrection
  normals.fixedCorrection = fixedCorrections_[segment];
  normals.straight = creaseEdges_[segment];
  return normals;
}

ProjectionResult MasterSurface::projectOn(int segment, const Eigen::Vector3d& point,
                                          const Eigen::Vector2d& guess,
                                          const Eigen::Matrix3Xd& coordinates) const {
  const NodeMatrix<double> nodes = segmentNodes(segment, coordinates);
  const ProjectionResult faceted = closestPointProjection(type_, nodes, point, guess);
  // Smoothed: refine on the Nagata patch only near the segment. The patch is a cubic in xi
  // whose extrapolation far beyond the segment curls back, and a point far away (a segment
  // of the search grid's cell) found spurious stationary points of the distance there
  // (slave points "projected" onto a segment 3 units away, at a gap of -3.8). The faceted
  // projection decides whether the point is near the segment; the patch differs from it by
  // O(h^2) curvature, far less than kSmoothRefineReach.
  if (!smooth_ || !faceted.converged || largestExcess(faceted.xi) > kSmoothRefineReach) {
    return faceted;
  }
  const NodalNormals normals = segmentNormals(segment);
  return closestPointProjection(type_, nodes, point, faceted.xi, {}, &normals);
}

double MasterSurface::distanceTo(int segment, const Eigen::Vector2d& xi,
                                 const Eigen::Vector3d& point,
                                 const Eigen::Matrix3Xd& coordinates) const {
  const NodalNormals normals = smooth_ ? segmentNormals(segment) : NodalNormals{};
  Eigen::Vector3d rho;
  std::array<Eigen::Vector3d, 2> tangents;
  interpolateSegment(type_, segmentNodes(segment, coordinates), smooth_ ? &normals : nullptr, xi[0],
                     xi[1], rho, tangents, nullptr);
  return (point - rho).norm();
}

MasterSurface::CellKey MasterSurface::cellKey(const Eigen::Vector3i& cell) const {
  constexpr long long kOffset = 1 << 20;
  constexpr int kBits = 21;
  return ((cell.x() + kOffset) << (2 * kBits)) | ((cell.y() + kOffset) << kBits) |
         (cell.z() + kOffset);
}

Eigen::Vector3i MasterSurface::cellOf(const Eigen::Vector3d& point) const {
  return ((point - gridOrigin_) / cellSize_).array().floor().cast<int>();
}

void MasterSurface::buildSearchGrid(const Eigen::Matrix3Xd& coordinates, double reachInSegments) {
  cells_.clear();
  if (segmentCount() == 0) return;
  std::vector<Eigen::AlignedBox3d> boxes(segmentCount());
  double sizeSum = 0;
  for (int s = 0; s < segmentCount(); ++s) {
    for (int k = 0; k < nodesPerSegment(); ++k) boxes[s].extend(coordinates.col(segments_(s, k)));
    sizeSum += boxes[s].sizes().maxCoeff();
  }
  typicalSize_ = sizeSum / segmentCount();
  // Boxes grow by the reach and by a fraction of the segment size (curved Quad9 segments bulge
  // beyond their nodes' hull only slightly).
  const double inflation = (reachInSegments + 0.25) * typicalSize_;
  cellSize_ = typicalSize_ + 2 * inflation;
  gridOrigin_ = coordinates.col(segments_(0, 0));
  for (int s = 0; s < segmentCount(); ++s) {
    const Eigen::Vector3d low = boxes[s].min().array() - inflation;
    const Eigen::Vector3d high = boxes[s].max().array() + inflation;
    const Eigen::Vector3i first = cellOf(low), last = cellOf(high);
    for (int i = first.x(); i <= last.x(); ++i) {
      for (int j = first.y(); j <= last.y(); ++j) {
        for (int k = first.z(); k <= last.z(); ++k) cells_[cellKey({i, j, k})].push_back(s);
      }
    }
  }
}

SegmentProjection MasterSurface::walk(int start, const Eigen::Vector2d& guess,
                                      const Eigen::Vector3d& point,
                                      const Eigen::Matrix3Xd& coordinates, bool hopped) const {
  const double stayTolerance = hopped ? kHopStayTolerance : kStayOnSegmentTolerance;
  std::vector<int> visited;
  std::vector<Eigen::Vector2d> visitedXi;
  auto projectionOn = [&](int segment, const Eigen::Vector2d& xi) -> SegmentProjection {
    return {segment, xi, distanceTo(segment, xi, point, coordinates)};
  };
  int segment = start;
  Eigen::Vector2d initial = guess;
  for (int hop = 0; hop < kMaxWalkHops && segment >= 0; ++hop) {
    visited.push_back(segment);
    const ProjectionResult p = projectOn(segment, point, initial, coordinates);
    if (!p.converged) {
      SegmentProjection notFound;
      notFound.projectionBrokeDown = p.brokeDown && !apartFrom(segment, point, coordinates);
      return notFound;
    }
    visitedXi.push_back(p.xi);
    if (accepts(segment, p.xi, hop == 0 ? stayTolerance : kInsideTolerance)) {
      return projectionOn(segment, p.xi);
    }
    int next = -1;
    // Whether every edge it leaves through leads back to the walk (or is a free edge it leaves
    // by no more than accepts() tolerates: a ridge may end at the master's boundary).
    bool leavesOnlyToVisited = true;
    for (int edge : violatedEdges(p.xi)) {
      const int candidate = neighbour(segment, edge);
      if (candidate < 0) {
        if (edgeExcess(p.xi, edge) > freeEdgeReach()) leavesOnlyToVisited = false;
      } else if (std::find(visited.begin(), visited.end(), candidate) == visited.end()) {
        next = candidate;
        break;
      }
    }
    if (next < 0 && leavesOnlyToVisited) {
      // Above a ridge (see kRidgeTolerance): keep the segment the walk started on, so that the
      // point does not change segment between Newton iterations, else the least exceeded one.
      std::size_t chosen = 0;
      if (largestExcess(visitedXi[0]) > kRidgeTolerance) {
        for (std::size_t k = 1; k < visited.size(); ++k) {
          if (largestExcess(visitedXi[k]) < largestExcess(visitedXi[chosen])) chosen = k;
        }
      }
      if (largestExcess(visitedXi[chosen]) > kRidgeTolerance) return {};
      return projectionOn(visited[chosen], visitedXi[chosen]);
    }
    segment = next;
    initial.setZero();
  }
  return {};
}

// Whether `point` is beyond the reach of `segment` (distanceBound) on the open side of its
// centre's tangent plane, where it cannot touch the segment whatever its projection does. The
// Newton projection of such a point need not converge: a block point beside a ball's cap, 1.55
// away from a segment 0.3 across, crept through the segment's bilinear extension by 1e-3 in xi
// per iteration (the Gauss-Newton fallback on its saddle) and stopped a run on "projection
// broke down" (ball_sts_soft_mu03.deck, t = 0.83).
bool MasterSurface::apartFrom(int segment, const Eigen::Vector3d& point,
                              const Eigen::Matrix3Xd& coordinates) const {
  if (distanceBound(segment, point, coordinates) <= 0) return false;
  Eigen::Vector3d centre;
  std::array<Eigen::Vector3d, 2> tangents;
  interpolateSegment(type_, segmentNodes(segment, coordinates),
                     static_cast<const NodalNormals*>(nullptr), 0.0, 0.0, centre, tangents,
                     nullptr);
  return (point - centre).dot(unitNormal(tangents)) > 0;
}

// A lower bound of the distance from `point` to any projection search() can accept on
// `segment`: the distance to the box of its current nodes grown by half its largest extent. An
// accepted parameter lies at most kFreeEdgeTolerance + kFreeEdgeBand (0.21 of the parameter
// half-width, i.e. 0.11 of an edge) beyond the segment, and a Quad9 or Nagata patch bulges out
// of its nodes' hull by a fraction of an edge; both stay inside that margin.
double MasterSurface::distanceBound(int segment, const Eigen::Vector3d& point,
                                    const Eigen::Matrix3Xd& coordinates) const {
  Eigen::AlignedBox3d box;
  for (int k = 0; k < nodesPerSegment(); ++k) box.extend(coordinates.col(segments_(segment, k)));
  const double margin = 0.5 * box.sizes().maxCoeff();
  const Eigen::Vector3d outside = ((box.min().array() - margin) - point.array())
                                      .max(point.array() - (box.max().array() + margin))
                                      .max(0.0);
  return outside.norm();
}

SegmentProjection MasterSurface::search(const Eigen::Vector3d& point,
                                        const Eigen::Matrix3Xd& coordinates) const {
  SegmentProjection best;
  SegmentProjection nearestOutside;  // the closest projection beyond its segment
  const auto cell = cells_.find(cellKey(cellOf(point)));
  if (cell == cells_.end()) return best;
  // Projections in the order of their distance bounds, stopping once the bound exceeds the
  // best accepted distance: a cell of a thin mesh holds 230-280 segments, and projecting onto
  // each made the first search 40x a slide search (docs/performance/README.md, "Contact
  // search"). Ties go to the lower segment index, the choice of a scan in index order, so the
  // result is the exhaustive scan's.
  thread_local std::vector<std::pair<double, int>> order;
  order.clear();
  for (int segment : cell->second)
    order.emplace_back(distanceBound(segment, point, coordinates), segment);
  std::sort(order.begin(), order.end());
  auto better = [](const SegmentProjection& candidate, const SegmentProjection& slot) {
    return !slot.found() || candidate.distance < slot.distance ||
           (candidate.distance == slot.distance && candidate.segment < slot.segment);
  };
  for (const auto& [bound, segment] : order) {
    if (best.found() && bound > best.distance) break;
    const ProjectionResult p = projectOn(segment, point, Eigen::Vector2d::Zero(), coordinates);
    if (!p.converged) continue;
    const SegmentProjection candidate{segment, p.xi, distanceTo(segment, p.xi, point, coordinates)};
    SegmentProjection& slot = accepts(segment, p.xi, kInsideTolerance) ? best : nearestOutside;
    if (better(candidate, slot)) slot = candidate;
  }
  // No segment holds the projection: the point may lie above a ridge (see kRidgeTolerance),
  // which the walk from the nearest segment recognizes. (Without an accepted projection the loop
  // above visited every segment of the cell, so nearestOutside is the exhaustive scan's.)
  if (!best.found() && nearestOutside.found()) {
    return walk(nearestOutside.segment, nearestOutside.xi, point, coordinates);
  }
  return best;
}

}  // namespace cc::contact
