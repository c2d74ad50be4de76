// Rigid analytic surfaces (STAS): construction from the deck and point-wise queries.
#include "contact/rigid_surface.hpp"

namespace cc::contact {

namespace {
Eigen::Vector3d toVector(const Vec3& v) { return {v[0], v[1], v[2]}; }
}  // namespace

RigidSurface RigidSurface::fromSpec(const RigidSurfaceSpec& spec) {
  RigidSurface s;
  s.shape = spec.shape;
  s.origin = toVector(spec.origin);
  s.normal = toVector(spec.normal).normalized();
  s.axis = toVector(spec.axis).normalized();
  s.radius = spec.radius;
  s.curvature = spec.curvature;
  return s;
}

double RigidSurface::level(const Eigen::Vector3d& point) const {
  const Eigen::Vector3d relative = point - origin;
  switch (shape) {
    case RigidSurfaceSpec::Shape::Plane: return relative.dot(normal);
    case RigidSurfaceSpec::Shape::Sphere: return relative.squaredNorm() - radius * radius;
    case RigidSurfaceSpec::Shape::Cylinder: {
      const Eigen::Vector3d d = relative - axis * axis.dot(relative);
      return d.squaredNorm() - radius * radius;
    }
    case RigidSurfaceSpec::Shape::ParabolicCylinder: {
      const double x = relative.dot(axis.cross(normal));
      return relative.dot(normal) - curvature * x * x;
    }
  }
  return 0;
}

Eigen::Vector3d RigidSurface::outwardNormal(const Eigen::Vector3d& point) const {
  const Eigen::Vector3d relative = point - origin;
  switch (shape) {
    case RigidSurfaceSpec::Shape::Plane: return normal;
    case RigidSurfaceSpec::Shape::Sphere: return relative.normalized();
    case RigidSurfaceSpec::Shape::Cylinder:
      return (relative - axis * axis.dot(relative)).normalized();
    case RigidSurfaceSpec::Shape::ParabolicCylinder: {
      const Eigen::Vector3d ex = axis.cross(normal);
      const double x = relative.dot(ex);
      return (normal - 2.0 * curvature * x * ex).normalized();
    }
  }
  return normal;
}

}  // namespace cc::contact
