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
  shape::SurfaceType segmentType = shape::SurfaceType::Quad4;
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
                    const PointLayout& layout, const Scalar& xi1, const Scalar& xi2) {
  kin.frame = surfaceFrame(layout.masterType, masterNodes, xi1, xi2, layout.currentNormals());
  const shape::SurfaceShape<Scalar> shape = shape::surfaceShape(layout.masterType, xi1, xi2);
  for (int k = 0; k < shape.count; ++k) kin.masterShape[k] = shape.value[k];
  if (layout.smoothMaster) kin.edgeBlend = nagataBlend(xi1, xi2).value;
}

// The master material point of the last converged projection, taken with the current
// coordinates on its own segment: rho_C(n) + u_C(n) of eq. (47), and there the traction of the
// last converged step carried along with the master surface (its covariant components T_i^(n)
// kept, the contravariant basis rho^i current): the pull-back to the reference configuration and
// push-forward to the current one that section 2.3.2 describes.
template <class Scalar>
void previousMaterialPoint(const NodeMatrix<Scalar>& itemNodes, const PointLayout& layout,
                           const NodeMatrix<Scalar>& masterNodes, const PointHistory& history,
                           Vec3<Scalar>& point, Vec3<Scalar>& convectedTraction) {
  const bool sameSegment = layout.previousMasterCount == 0;
  const shape::SurfaceType type = sameSegment ? layout.masterType : layout.previousMasterType;
  const NodeMatrix<Scalar> previousNodes =
      sameSegment ? masterNodes
                  : gatherNodes(itemNodes, layout.previousMasterLocal, layout.previousMasterCount);
  std::array<Vec3<Scalar>, 2> tangents;
  interpolateSegment(type, previousNodes, layout.previousNormals(), Scalar(history.xi[0]),
                     Scalar(history.xi[1]), point, tangents, nullptr);
  const Mat2<Scalar> inverseMetric = contravariantMetric(covariantMetric(tangents));
  convectedTraction.setZero();
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      convectedTraction += history.tractionCovariant[i] * inverseMetric(i, j) * tangents[j];
    }
  }
}

}  // namespace detail

// NTS and STS: the slave point r_s is projected onto the master segment (converged parameter
// `xi`, re-taken differentiably), g = (r_s - rho) . n, eq. (27).
template <class Scalar>
PointKinematics<Scalar> projectedPointKinematics(const NodeMatrix<Scalar>& itemNodes,
                                                 const PointLayout& layout, const SlaveSide& slave,
                                                 const Eigen::Vector2d& xi,
                                                 const PointHistory& history) {
  PointKinematics<Scalar> kin;
  kin.slavePoint.setZero();
  for (int a = 0; a < layout.slaveCount; ++a) {
    kin.slavePoint += layout.slaveShape[a] * itemNodes.col(layout.slaveLocal[a]);
  }
  const NodeMatrix<Scalar> masterNodes =
      detail::gatherNodes(itemNodes, layout.masterLocal, layout.masterCount);
  const Eigen::Matrix<Scalar, 2, 1> parameter = differentiableProjection(
      layout.masterType, masterNodes, kin.slavePoint, xi, layout.currentNormals());
  detail::setMasterFrame(kin, masterNodes, layout, parameter[0], parameter[1]);
  kin.xi = parameter;
  kin.gap = (kin.slavePoint - kin.frame.rho).dot(kin.frame.normal);
  kin.slip.setZero();
  kin.convectedTraction.setZero();
  if (history.projected) {
    Vec3<Scalar> previousPoint;
    detail::previousMaterialPoint(itemNodes, layout, masterNodes, history, previousPoint,
                                  kin.convectedTraction);
    kin.slip = kin.frame.rho - previousPoint;  // eq. (47)
  }
  if (layout.slaveCount == 1) {
    kin.weight = Scalar(slave.nodalArea);
  } else if (slave.frozenAreaElement) {
    kin.weight = Scalar(*slave.frozenAreaElement * slave.gaussWeight);
  } else {
    // Eq. (10) on the slave segment: ds = |r_s,1 x r_s,2| dxi^1 dxi^2.
    const NodeMatrix<Scalar> slaveNodes =
        detail::gatherNodes(itemNodes, layout.slaveLocal, layout.slaveCount);
    const shape::SurfaceShape<Scalar> shape = shape::surfaceShape(
        slave.segmentType, Scalar(slave.gaussPoint[0]), Scalar(slave.gaussPoint[1]));
    Vec3<Scalar> point;
    std::array<Vec3<Scalar>, 2> tangents;
    interpolateSurface(slaveNodes, shape, point, tangents, nullptr);
    kin.weight = tangents[0].cross(tangents[1]).norm() * slave.gaussWeight;
  }
  // Beyond a free edge of the master the force fades out (contact_point.hpp, kFreeEdgeBand).
  if (layout.freeEdges != 0) kin.weight *= freeEdgeFactor(parameter, layout.freeEdges);
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
  detail::setMasterFrame(kin, masterNodes, layout, Scalar(xi[0]), Scalar(xi[1]));
  kin.xi = xi.cast<Scalar>();
  const std::optional<Scalar> gap =
      normalLineGap(surface, surfaceOffset, kin.frame.rho, kin.frame.normal);
  if (!gap) return std::nullopt;
  kin.gap = *gap;
  kin.slavePoint = kin.frame.rho + kin.gap * kin.frame.normal;
  kin.weight = kin.frame.areaElement * gaussWeight;
  kin.slip.setZero();
  kin.convectedTraction.setZero();
  if (history.projected) {
    const Vec3<Scalar> relativeMotion = kin.frame.rho - history.masterPoint.cast<Scalar>() -
                                        (surfaceOffset - history.surfaceOffset).cast<Scalar>();
    kin.slip = -relativeMotion;
    // The Gauss point is the master material point itself: T_i^(n) rho^i(current).
    kin.convectedTraction = history.tractionCovariant[0] * kin.frame.rhoContra[0] +
                            history.tractionCovariant[1] * kin.frame.rhoContra[1];
  }
  return kin;
}

}  // namespace cc::contact
