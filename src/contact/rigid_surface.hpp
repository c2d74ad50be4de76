// Rigid analytic surfaces for the segment-to-analytical-surface (STAS) approach, section 6.3.1:
// plane, circular cylinder, parabolic cylinder z = c x^2 and sphere, each translated rigidly by
// a prescribed motion. The contact point on the surface is where the master normal line
// rho + xi^3 n meets it, eq. (117); xi^3 is the gap. All four shapes have closed forms (for the
// parabolic cylinder this is the closed form of the Newton iteration (122)-(124)), templated so
// the exact tangent can differentiate them.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <optional>

namespace cc::contact {

struct RigidSurface {
  enum class Shape { Plane, Cylinder, ParabolicCylinder, Sphere };
  Shape shape = Shape::Plane;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // outward side (towards the deformable body)
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();    // cylinders' generatrix direction
  double radius = 0;
  double curvature =
      0;  // parabolic cylinder: z = c x^2 in the frame (x = axis x normal, z = normal)

  // Outward unit normal of the surface at a point on it (for output and sanity checks).
  Eigen::Vector3d outwardNormal(const Eigen::Vector3d& point) const;
  // Signed distance-like level function: < 0 inside the rigid body, 0 on the surface.
  double level(const Eigen::Vector3d& point) const;
};

namespace detail {

// The root of L(g) = a g^2 + b g + c = 0 at which the normal line enters the rigid body, i.e.
// where L (> 0 outside, < 0 inside) decreases: L'(g) = 2 a g + b = -sqrt(D), so
// g = (-b - sqrt(D)) / (2a) = 2c / (-b + sqrt(D)); the second form is used when b < 0 to avoid
// cancellation, and also covers the linear case a = 0.
template <class Scalar>
std::optional<Scalar> enteringRoot(const Scalar& a, const Scalar& b, const Scalar& c) {
  using std::abs;
  using std::sqrt;
  const Scalar discriminant = b * b - 4.0 * a * c;
  if (discriminant < 0.0) return std::nullopt;  // the normal line misses the surface
  const Scalar root = sqrt(discriminant);
  if (b < 0.0) return Scalar(2.0 * c / (root - b));
  if (a == 0.0) return std::nullopt;  // linear and not entering (parallel or leaving)
  return Scalar((-b - root) / (2.0 * a));
}

}  // namespace detail

// xi^3 of eq. (117): the distance along the master normal n from rho to the rigid surface
// (negative when rho is inside the rigid body, i.e. penetration). Empty when the normal line
// does not enter the surface. `offset` is the surface's current rigid translation.
template <class Scalar>
std::optional<Scalar> normalLineGap(const RigidSurface& surface, const Eigen::Vector3d& offset,
                                    const Eigen::Matrix<Scalar, 3, 1>& rho,
                                    const Eigen::Matrix<Scalar, 3, 1>& n) {
  using Vec = Eigen::Matrix<Scalar, 3, 1>;
  const Vec relative = rho - (surface.origin + offset).template cast<Scalar>();
  const Vec nu = surface.normal.template cast<Scalar>();
  const Vec axis = surface.axis.template cast<Scalar>();
  switch (surface.shape) {
    case RigidSurface::Shape::Plane: {
      // level = (p - o) . nu, linear in g.
      return detail::enteringRoot(Scalar(0.0), Scalar(n.dot(nu)), Scalar(relative.dot(nu)));
    }
    case RigidSurface::Shape::Sphere: {
      // level = |p - o|^2 - R^2
      return detail::enteringRoot(Scalar(n.dot(n)), Scalar(2.0 * n.dot(relative)),
                                  Scalar(relative.dot(relative) - surface.radius * surface.radius));
    }
    case RigidSurface::Shape::Cylinder: {
      // level = |p_perp|^2 - R^2 with p_perp the part orthogonal to the axis.
      const Vec d = relative - axis * axis.dot(relative);
      const Vec m = n - axis * axis.dot(n);
      return detail::enteringRoot(Scalar(m.dot(m)), Scalar(2.0 * m.dot(d)),
                                  Scalar(d.dot(d) - surface.radius * surface.radius));
    }
    case RigidSurface::Shape::ParabolicCylinder: {
      // level = z - c x^2 in the local frame x = axis x nu, z = nu (body below the parabola).
      const Vec ex = axis.cross(nu);
      const Scalar x0 = relative.dot(ex), z0 = relative.dot(nu);
      const Scalar nx = n.dot(ex), nz = n.dot(nu);
      const double c = surface.curvature;
      return detail::enteringRoot(Scalar(-c * nx * nx), Scalar(nz - 2.0 * c * x0 * nx),
                                  Scalar(z0 - c * x0 * x0));
    }
  }
  return std::nullopt;
}

}  // namespace cc::contact
