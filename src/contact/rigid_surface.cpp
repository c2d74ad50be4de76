// Rigid analytic surfaces (STAS): point-wise queries (the model builder constructs them from the
// deck).
#include "contact/rigid_surface.hpp"

namespace cc::contact {

double RigidSurface::level(const Eigen::Vector3d& point) const {
  const Eigen::Vector3d relative = point - origin;
  switch (shape) {
    case RigidSurface::Shape::Plane:
      return relative.dot(normal);
    case RigidSurface::Shape::Sphere:
      return relative.squaredNorm() - radius * radius;
    case RigidSurface::Shape::Cylinder: {
      const Eigen::Vector3d d = relative - axis * axis.dot(relative);
      return d.squaredNorm() - radius * radius;
    }
    case RigidSurface::Shape::ParabolicCylinder: {
      const double x = relative.dot(axis.cross(normal));
      return relative.dot(normal) - curvature * x * x;
    }
  }
  return 0;
}

Eigen::Vector3d RigidSurface::outwardNormal(const Eigen::Vector3d& point) const {
  const Eigen::Vector3d relative = point - origin;
  switch (shape) {
    case RigidSurface::Shape::Plane:
      return normal;
    case RigidSurface::Shape::Sphere:
      return relative.normalized();
    case RigidSurface::Shape::Cylinder:
      return (relative - axis * axis.dot(relative)).normalized();
    case RigidSurface::Shape::ParabolicCylinder: {
      const Eigen::Vector3d ex = axis.cross(normal);
      const double x = relative.dot(ex);
      return (normal - 2.0 * curvature * x * ex).normalized();
    }
  }
  return normal;
}

}  // namespace cc::contact
