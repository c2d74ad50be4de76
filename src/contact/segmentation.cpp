// Segment-exact STS integration: clipping in the slave parameter plane, triangle rules.
#include "contact/segmentation.hpp"

#include <array>
#include <cmath>

#include "contact/projection.hpp"
#include "fem/quadrature.hpp"

namespace cc::contact {

namespace {

// Pieces and fan triangles below this parametric area (of the square's 4) are slivers, e.g.
// where an image edge runs along a slave edge (matching meshes), and are dropped; the weights are
// then rescaled to the square's area. Far above round-off on purpose: with a threshold at 1e-14
// the slivers of two runs whose configurations differ by round-off (the same deck on 1 and on 2
// processes, 1e-9 apart) fell on different sides, and one run had a 3-point triangle more
// (parallel.segments). 1e-8 of 4 is a weight change of 2.5e-9 of the segment at most.
constexpr double kSliverArea = 1e-8;
// Master corners are projected onto the slave segment extrapolated up to this parameter.
constexpr double kImageBound = 10;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a[0] * b[1] - a[1] * b[0];
}

const Polygon2& unitSquare() {
  static const Polygon2 square = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  return square;
}

bool strictlyConvex(const Polygon2& p) {
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Eigen::Vector2d& a = p[k];
    const Eigen::Vector2d& b = p[(k + 1) % p.size()];
    const Eigen::Vector2d& c = p[(k + 2) % p.size()];
    if (!(cross(b - a, c - b) > 0)) return false;
  }
  return true;
}

// Triangle rules in barycentric coordinates (weights summing to 1): centroid (degree 1),
// Strang-Fix 3 points (degree 2), Dunavant/Strang-Fix 7 points (degree 5).
struct TrianglePoint {
  std::array<double, 3> lambda;
  double weight;
};

std::vector<TrianglePoint> triangleRule(int rulePoints) {
  constexpr double third = 1.0 / 3.0;
  if (rulePoints <= 1) return {{{third, third, third}, 1.0}};
  if (rulePoints == 2) {
    constexpr double a = 2.0 / 3.0, b = 1.0 / 6.0;
    return {{{a, b, b}, third}, {{b, a, b}, third}, {{b, b, a}, third}};
  }
  constexpr double a1 = 0.059715871789769820, b1 = 0.470142064105115090;
  constexpr double w1 = 0.132394152788506181;
  constexpr double a2 = 0.797426985353087322, b2 = 0.101286507323456339;
  constexpr double w2 = 0.125939180544827153;
  return {{{third, third, third}, 0.225},
          {{a1, b1, b1}, w1},
          {{b1, a1, b1}, w1},
          {{b1, b1, a1}, w1},
          {{a2, b2, b2}, w2},
          {{b2, a2, b2}, w2},
          {{b2, b2, a2}, w2}};
}

struct Piece {
  Polygon2 polygon;
  int image = -1;
};

// Splits `piece` by the convex image: the part inside it (labelled) and up to four convex
// pieces outside it, one beyond each edge line in turn.
void splitByImage(const Piece& piece, const Polygon2& image, int index, std::vector<Piece>& out) {
  Polygon2 rest = piece.polygon;
  for (std::size_t k = 0; k < image.size() && !rest.empty(); ++k) {
    const Eigen::Vector2d& a = image[k];
    const Eigen::Vector2d& b = image[(k + 1) % image.size()];
    Polygon2 outside = clipToLeftOf(rest, b, a);
    if (signedArea(outside) > kSliverArea) out.push_back({std::move(outside), piece.image});
    rest = clipToLeftOf(rest, a, b);
  }
  if (signedArea(rest) > kSliverArea) out.push_back({std::move(rest), index});
}

}  // namespace

double signedArea(const Polygon2& polygon) {
  double twice = 0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    twice += cross(polygon[k], polygon[(k + 1) % polygon.size()]);
  }
  return 0.5 * twice;
}

Polygon2 clipToLeftOf(const Polygon2& polygon, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  Polygon2 result;
  const Eigen::Vector2d direction = b - a;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d& p = polygon[k];
    const Eigen::Vector2d& q = polygon[(k + 1) % polygon.size()];
    const double sp = cross(direction, p - a), sq = cross(direction, q - a);
    if (sp >= 0) result.push_back(p);
    if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) {
      result.push_back(Eigen::Vector2d(p + sp / (sp - sq) * (q - p)));
    }
  }
  return result.size() >= 3 ? result : Polygon2{};
}

std::optional<Polygon2> masterImage(shape::SurfaceType slaveType,
                                    const NodeMatrix<double>& slaveNodes,
                                    const NodeMatrix<double>& masterCorners) {
  // A master segment up to a few times larger than the slave has corners far out in its
  // parameter plane.
  ProjectionOptions options;
  options.parameterBound = kImageBound;
  Polygon2 image;
  for (int k = 0; k < 4; ++k) {
    const ProjectionResult p = closestPointProjection(slaveType, slaveNodes, masterCorners.col(k),
                                                      Eigen::Vector2d::Zero(), options);
    if (!p.converged) return std::nullopt;
    image.push_back(p.xi);
  }
  // A master facing the slave maps clockwise (the normals are opposite).
  if (signedArea(image) < 0) std::swap(image[1], image[3]);
  if (!strictlyConvex(image)) return std::nullopt;
  return image;
}

double overlapWithSquare(const Polygon2& image) {
  Polygon2 overlap = unitSquare();
  for (std::size_t k = 0; k < image.size() && !overlap.empty(); ++k) {
    overlap = clipToLeftOf(overlap, image[k], image[(k + 1) % image.size()]);
  }
  return signedArea(overlap);
}

std::vector<SegmentPoint> segmentPoints(const std::vector<Polygon2>& images, int rulePoints) {
  std::vector<Piece> pieces = {{unitSquare(), -1}};
  for (std::size_t i = 0; i < images.size(); ++i) {
    std::vector<Piece> next;
    for (const Piece& piece : pieces) {
      // Labelled pieces are finished; an unlabelled one the image does not reach stays whole.
      Polygon2 overlap = piece.polygon;
      for (std::size_t k = 0; k < images[i].size() && !overlap.empty(); ++k) {
        overlap = clipToLeftOf(overlap, images[i][k], images[i][(k + 1) % images[i].size()]);
      }
      if (piece.image >= 0 || signedArea(overlap) <= kSliverArea) {
        next.push_back(piece);
      } else {
        splitByImage(piece, images[i], static_cast<int>(i), next);
      }
    }
    pieces = std::move(next);
  }
  std::vector<SegmentPoint> points;
  if (pieces.size() == 1) {  // nothing splits the square: the Gauss rule of the gauss option
    for (const auto& q : gaussQuad(rulePoints)) points.push_back({q.xi, q.weight, pieces[0].image});
    return points;
  }
  const std::vector<TrianglePoint> rule = triangleRule(rulePoints);
  for (const Piece& piece : pieces) {
    const Polygon2& p = piece.polygon;
    for (std::size_t k = 1; k + 1 < p.size(); ++k) {  // fan of the convex piece
      const double area = 0.5 * cross(p[k] - p[0], p[k + 1] - p[0]);
      if (area <= kSliverArea) continue;  // a (nearly) collinear vertex of the clipping
      for (const TrianglePoint& t : rule) {
        const Eigen::Vector2d xi = t.lambda[0] * p[0] + t.lambda[1] * p[k] + t.lambda[2] * p[k + 1];
        points.push_back({xi, t.weight * area, piece.image});
      }
    }
  }
  // The pieces cover the square (area 4) but for the dropped slivers.
  double total = 0;
  for (const SegmentPoint& point : points) total += point.weight;
  for (SegmentPoint& point : points) point.weight *= 4.0 / total;
  return points;
}

}  // namespace cc::contact
