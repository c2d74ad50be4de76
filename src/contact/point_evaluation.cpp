// One contact point: projection, kinematics, law, force and tangent, for each contact kind.
#include "contact/point_evaluation.hpp"

#include "contact/exact_tangent.hpp"
#include "contact/tangent_parts.hpp"

namespace cc::contact {

namespace {

NodeMatrix<double> masterNodesOf(const PointSetup& setup, const NodeMatrix<double>& nodes) {
  const PointLayout& layout = setup.layout;
  NodeMatrix<double> master(3, layout.masterCount);
  for (int k = 0; k < layout.masterCount; ++k) master.col(k) = nodes.col(layout.masterLocal[k]);
  return master;
}

Eigen::Vector3d slavePointOf(const PointSetup& setup, const NodeMatrix<double>& nodes) {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  for (int a = 0; a < setup.layout.slaveCount; ++a) {
    point += setup.layout.slaveShape[a] * nodes.col(setup.layout.slaveLocal[a]);
  }
  return point;
}

}  // namespace

PointEvaluation evaluatePoint(const PointSetup& setup, const NodeMatrix<double>& nodes) {
  PointEvaluation e;
  e.force.setZero(3 * setup.layout.nodeCount);
  if (setup.kind == PointKind::SegmentToAnalytical) {
    e.xi = setup.parameter;
    auto kin = analyticalSurfaceKinematics(nodes, setup.layout, setup.parameter, setup.gaussWeight,
                                           *setup.surface, setup.surfaceOffset, setup.history);
    if (!kin) return e;
    e.kinematics = *kin;
  } else {
    const ProjectionResult projection = closestPointProjection(
        setup.layout.masterType, masterNodesOf(setup, nodes), slavePointOf(setup, nodes),
        setup.parameter, {}, setup.layout.currentNormals());
    if (!projection.converged) return e;
    e.xi = projection.xi;
    e.kinematics = projectedPointKinematics(nodes, setup.layout, setup.slave, e.xi, setup.history);
  }
  e.valid = true;
  e.response = pointResponse(e.kinematics, setup.history, setup.law);
  pointForce(e.kinematics, e.response, setup.layout, e.force);
  return e;
}

void pointTangent(const PointSetup& setup, const NodeMatrix<double>& nodes,
                  const PointEvaluation& evaluation, TangentMode mode, const TangentParts& parts,
                  Eigen::MatrixXd& K) {
  const int dofs = 3 * setup.layout.nodeCount;
  if (!evaluation.valid || evaluation.response.state == ContactState::Open) {
    K.setZero(dofs, dofs);
    return;
  }
  if (mode == TangentMode::Paper) {
    const PointKinematics<double>& kin = evaluation.kinematics;
    Eigen::Vector3d gapDirection = kin.frame.normal;
    if (setup.kind == PointKind::SegmentToAnalytical) {
      // Eq. (117) linearized: the rigid point slides along the surface (normal nu), so
      // delta g = -(delta rho) . nu / (n . nu) up to the g delta n terms.
      const Eigen::Vector3d nu = setup.surface->outwardNormal(kin.slavePoint - setup.surfaceOffset);
      gapDirection = nu / kin.frame.normal.dot(nu);
    }
    paperTangent(kin, evaluation.response, setup.layout, evaluation.xi, setup.law, parts,
                 gapDirection, K);
    return;
  }
  if (setup.kind == PointKind::SegmentToAnalytical) {
    exactTangent(
        nodes, setup.layout, setup.history, setup.law,
        [&](const auto& active) {
          return analyticalSurfaceKinematics(active, setup.layout, setup.parameter,
                                             setup.gaussWeight, *setup.surface, setup.surfaceOffset,
                                             setup.history);
        },
        K);
    return;
  }
  exactTangent(
      nodes, setup.layout, setup.history, setup.law,
      [&](const auto& active) {
        return projectedPointKinematics(active, setup.layout, setup.slave, evaluation.xi,
                                        setup.history);
      },
      K);
}

}  // namespace cc::contact
