// Evaluation of one contact point from the current coordinates of its item's nodes: projection
// (NTS/STS) or normal-line intersection (STAS), kinematics, contact law, force, and the tangent
// (the paper's selected parts, or the exact one). The contact pairs call this per item; the
// tests call it directly to compare tangents with finite differences.
#pragma once

#include <Eigen/Core>

#include "contact/point_kinematics.hpp"
#include "contact/tangent_parts.hpp"

namespace cc::contact {

enum class PointKind { NodeToSegment, SegmentToSegment, SegmentToAnalytical };

struct PointSetup {
  PointKind kind = PointKind::NodeToSegment;
  PointLayout layout;
  SlaveSide slave;
  PointHistory history;
  LawParameters law;
  // NTS/STS: the initial guess of the projection; STAS: the fixed master Gauss point.
  Eigen::Vector2d parameter = Eigen::Vector2d::Zero();
  double gaussWeight = 0;                                   // STAS
  const RigidSurface* surface = nullptr;                    // STAS
  Eigen::Vector3d surfaceOffset = Eigen::Vector3d::Zero();  // STAS: current rigid translation
};

struct PointEvaluation {
  bool valid = false;  // projection converged (NTS/STS) / normal line met the surface (STAS)
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();  // master parameter of the contact point
  PointKinematics<double> kinematics;
  PointResponse<double> response;
  Eigen::VectorXd force;  // 3 * layout.nodeCount, zero when open or invalid
};

// nodes: 3 x layout.nodeCount current coordinates of the item's nodes.
PointEvaluation evaluatePoint(const PointSetup& setup, const NodeMatrix<double>& nodes);

// Tangent of an evaluated point: paper parts (with `parts`) or exact (AD). K sized here.
void pointTangent(const PointSetup& setup, const NodeMatrix<double>& nodes,
                  const PointEvaluation& evaluation, TangentMode mode, const TangentParts& parts,
                  Eigen::MatrixXd& K);

}  // namespace cc::contact
