// Kinematics of one contact point for each contact kind, from the current coordinates of the
// item's nodes: node-to-segment (slave node), segment-to-segment (slave Gauss point) and
// segment-to-analytical-surface (master Gauss point against a rigid surface). Templated on the
// scalar type; with an AD scalar every dependence on the nodes, including the projection
// parameter and the slave area element, is differentiated (the exact tangent).
#pragma once

#include <Eigen/Core>
#include <optional>

#include "contact/contact_point.hpp"
#include "contact/projection.hpp"
#include "contact/rigid_surface.hpp"

namespace cc::contact {

// How the slave side of a point is described.
struct SlaveSide {
  // NTS: tributary area of the slave node (reference configuration, held constant).
  double nodalArea = 0;
  // STS: the slave segment and the Gauss point on it.
  SegmentType segmentType = SegmentType::Quad4;
  Eigen::Vector2d gaussPoint = Eigen::Vector2d::Zero();
  double gaussWeight = 0;
  // STS: use this area element instead of the current one (the paper keeps ds constant in
  // the linearization, section 4.1; tests freeze it to check that statement exactly).
  std::optional<double> frozenAreaElement;
};

namespace detail {

template <class Scalar>
NodeMatrix<Scalar> gatherNodes(const NodeMatrix<Scalar>& itemNodes, const std::array<int, 9>& local,
                               int count) {
  NodeMatrix<Scalar> nodes(3, count);
  for (int k = 0; k < count; ++k) nodes.col(k) = itemNodes.col(local[k]);
  return nodes;
}

template <class Scalar>
void setMasterFrame(PointKinematics<Scalar>& kin, const NodeMatrix<Scalar>& masterNodes,
                    SegmentType type, const Scalar& xi1, const Scalar& xi2) {
  kin.frame = surfaceFrame(type, masterNodes, xi1, xi2);
  const SurfaceShape<Scalar> shape = surfaceShape(type, xi1, xi2);
  for (int k = 0; k < shape.count; ++k) kin.masterShape[k] = shape.value[k];
}

// Eq. (47): Delta rho = rho(xi_(n+1)) - rho(xi_(n)) where the master material point of the last
// projection is taken with the current coordinates (rho_C(n) + u_C(n)), on its own segment.
template <class Scalar>
Vec3<Scalar> slipSincePreviousProjection(const NodeMatrix<Scalar>& itemNodes,
                                         const PointLayout& layout,
                                         const NodeMatrix<Scalar>& masterNodes,
                                         const PointHistory& history, const Vec3<Scalar>& rho) {
  if (!history.projected) return Vec3<Scalar>::Zero();
  const bool sameSegment = layout.previousMasterCount == 0;
  const SegmentType type = sameSegment ? layout.masterType : layout.previousMasterType;
  const NodeMatrix<Scalar> previousNodes =
      sameSegment ? masterNodes
                  : gatherNodes(itemNodes, layout.previousMasterLocal, layout.previousMasterCount);
  const SurfaceShape<Scalar> shape =
      surfaceShape(type, Scalar(history.xi[0]), Scalar(history.xi[1]));
  Vec3<Scalar> previousPoint = Vec3<Scalar>::Zero();
  for (int k = 0; k < shape.count; ++k) previousPoint += shape.value[k] * previousNodes.col(k);
  return rho - previousPoint;
}

}  // namespace detail

// NTS and STS: the slave point r_s is projected onto the master segment (converged parameter
// `xi`, re-taken differentiably), g = (r_s - rho) . n, eq. (27).
template <class Scalar>
PointKinematics<Scalar> projectedPointKinematics(const NodeMatrix<Scalar>& itemNodes,
                                                 const PointLayout& layout,
                                                 const SlaveSide& slave,
                                                 const Eigen::Vector2d& xi,
                                                 const PointHistory& history) {
  PointKinematics<Scalar> kin;
  kin.slavePoint.setZero();
  for (int a = 0; a < layout.slaveCount; ++a) {
    kin.slavePoint += layout.slaveShape[a] * itemNodes.col(layout.slaveLocal[a]);
  }
  const NodeMatrix<Scalar> masterNodes =
      detail::gatherNodes(itemNodes, layout.masterLocal, layout.masterCount);
  const Eigen::Matrix<Scalar, 2, 1> parameter =
      differentiableProjection(layout.masterType, masterNodes, kin.slavePoint, xi);
  detail::setMasterFrame(kin, masterNodes, layout.masterType, parameter[0], parameter[1]);
  kin.xi = parameter;
  kin.gap = (kin.slavePoint - kin.frame.rho).dot(kin.frame.normal);
  kin.slip =
      detail::slipSincePreviousProjection(itemNodes, layout, masterNodes, history, kin.frame.rho);
  if (layout.slaveCount == 1) {
    kin.weight = Scalar(slave.nodalArea);
  } else if (slave.frozenAreaElement) {
    kin.weight = Scalar(*slave.frozenAreaElement * slave.gaussWeight);
  } else {
    // Eq. (10) on the slave segment: ds = |r_s,1 x r_s,2| dxi^1 dxi^2.
    const NodeMatrix<Scalar> slaveNodes =
        detail::gatherNodes(itemNodes, layout.slaveLocal, layout.slaveCount);
    const SurfaceShape<Scalar> shape = surfaceShape(
        slave.segmentType, Scalar(slave.gaussPoint[0]), Scalar(slave.gaussPoint[1]));
    Vec3<Scalar> point;
    std::array<Vec3<Scalar>, 2> tangents;
    interpolateSurface(slaveNodes, shape, point, tangents, nullptr);
    kin.weight = tangents[0].cross(tangents[1]).norm() * slave.gaussWeight;
  }
  return kin;
}

// STAS: the master Gauss point xi is fixed; the rigid surface point lies on the master normal
// line, eq. (117), at distance xi^3 = g. The slip is Delta rho = -u, eq. (48), with u the
// master point's displacement relative to the rigid surface since the last converged step.
// Returns nothing when the normal line does not meet the surface (point open).
template <class Scalar>
std::optional<PointKinematics<Scalar>> analyticalSurfaceKinematics(
    const NodeMatrix<Scalar>& itemNodes, const PointLayout& layout, const Eigen::Vector2d& xi,
    double gaussWeight, const RigidSurface& surface, const Eigen::Vector3d& surfaceOffset,
    const PointHistory& history) {
  PointKinematics<Scalar> kin;
  const NodeMatrix<Scalar> masterNodes =
      detail::gatherNodes(itemNodes, layout.masterLocal, layout.masterCount);
  detail::setMasterFrame(kin, masterNodes, layout.masterType, Scalar(xi[0]), Scalar(xi[1]));
  kin.xi = xi.cast<Scalar>();
  const std::optional<Scalar> gap =
      normalLineGap(surface, surfaceOffset, kin.frame.rho, kin.frame.normal);
  if (!gap) return std::nullopt;
  kin.gap = *gap;
  kin.slavePoint = kin.frame.rho + kin.gap * kin.frame.normal;
  kin.weight = kin.frame.areaElement * gaussWeight;
  if (history.projected) {
    const Vec3<Scalar> relativeMotion = kin.frame.rho - history.masterPoint.cast<Scalar>() -
                                        (surfaceOffset - history.surfaceOffset).cast<Scalar>();
    kin.slip = -relativeMotion;
  } else {
    kin.slip.setZero();
  }
  return kin;
}

}  // namespace cc::contact
