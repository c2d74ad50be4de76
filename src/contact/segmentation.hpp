// Segment-exact STS integration (issue 16, part 1): the partition of a slave segment's parameter
// square [-1, 1]^2 by the images of the master segments it overlaps, and the integration points
// placed on the pieces. Segmentation as in mortar methods (Puso & Laursen 2004, Popp et al.
// 2010), but the points it makes are ordinary covariant STS points: each is projected onto the
// master and evaluated by the unchanged kernels, eqs. (27), (47), (60) and Tables 1-2; only its
// place and weight on the slave segment differ from the Gauss rule.
//
// Why in the slave parameter plane: a point's weight then stays the parametric weight times the
// slave area element |r_,1 x r_,2| of eq. (10), as for the Gauss points, so the kernels and the
// exact tangent need no change, and the weights of a slave segment integrate its area exactly
// on any flat segment (the area element is linear in xi there). The master edges are taken as
// the straight lines between the images of the master corners: exact where the slave segment
// is a parallelogram, an O(h^2) approximation of the image curves otherwise.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "contact/geometry.hpp"

namespace cc::contact {

using Polygon2 = std::vector<Eigen::Vector2d>;

struct SegmentPoint {
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();  // on the slave segment
  double weight = 0;  // parametric: the point integrates |r_,1 x r_,2| weight, eq. (10)
  int image = -1;     // the master image its piece lies in (index into the list), -1: none
};

// Signed area of a polygon (counter-clockwise positive).
double signedArea(const Polygon2& polygon);

// The part of a convex polygon to the left of the directed line a -> b (Sutherland-Hodgman).
Polygon2 clipToLeftOf(const Polygon2& polygon, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// The image of a master segment in the parameter plane of a slave segment: each master corner
// (masterCorners: 3 x 4) projected onto the slave segment, extrapolated beyond it (closest-point
// projection, eqs. (21)-(25) with the slave as the surface). Counter-clockwise; nothing when a
// projection fails or the image is not a strictly convex quadrilateral (a master folded over
// the slave: that region keeps its unsplit rule).
std::optional<Polygon2> masterImage(shape::SurfaceType slaveType,
                                    const NodeMatrix<double>& slaveNodes,
                                    const NodeMatrix<double>& masterCorners);

// Area of the overlap of a convex counter-clockwise image with the square [-1, 1]^2.
double overlapWithSquare(const Polygon2& image);

// The points of one slave segment. The square is split by every image in turn into the part
// inside the image (finished) and convex pieces outside it (split further by the later images),
// so the pieces partition the square exactly whatever the images are. A square no image splits
// keeps the rulePoints x rulePoints Gauss rule (today's points); otherwise each piece is fanned
// into triangles with a triangle rule of degree 1, 2 or 5 (1, 3 or 7 points; rulePoints 1, 2,
// >= 3). The weights sum to the square's area 4 up to round-off.
std::vector<SegmentPoint> segmentPoints(const std::vector<Polygon2>& images, int rulePoints);

}  // namespace cc::contact
