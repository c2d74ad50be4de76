// The contact points of each kind (NTS, STS, STAS), their trial state and their output record.
#include "contact/contact_points.hpp"

#include <cmath>
#include <limits>
#include <map>

#include "contact/contact_point.hpp"
#include "fem/quadrature.hpp"

namespace cc::contact {

namespace {

shape::SurfaceType segmentTypeOf(const FaceSet& faces) {
  return faces.type == CellType::Quad9 ? shape::SurfaceType::Quad9 : shape::SurfaceType::Quad4;
}

// Area element |rho_1 x rho_2| of a face at xi, reference configuration.
double areaElement(shape::SurfaceType type, const NodeMatrix<double>& nodes,
                   const Eigen::Vector2d& xi) {
  const shape::SurfaceShape<double> shape = shape::surfaceShape(type, xi[0], xi[1]);
  Eigen::Vector3d point;
  std::array<Eigen::Vector3d, 2> tangents;
  interpolateSurface(nodes, shape, point, tangents, nullptr);
  return tangents[0].cross(tangents[1]).norm();
}

NodeMatrix<double> faceNodes(const FaceSet& faces, int face, const Eigen::Matrix3Xd& x) {
  NodeMatrix<double> nodes(3, faces.connectivity.cols());
  for (int k = 0; k < nodes.cols(); ++k) nodes.col(k) = x.col(faces.connectivity(face, k));
  return nodes;
}

// Integration rule for the NTS tributary areas (exact for the Quad9 shape functions on flat
// faces).
constexpr int kTributaryAreaPoints = 3;

}  // namespace

std::vector<PairPoint> nodeToSegmentPoints(const Mesh& mesh, const FaceSet& slave) {
  std::vector<PairPoint> points;
  std::map<int, double> area;
  const shape::SurfaceType type = segmentTypeOf(slave);
  for (int face = 0; face < slave.connectivity.rows(); ++face) {
    const NodeMatrix<double> nodes = faceNodes(slave, face, mesh.coordinates);
    for (const auto& q : gaussQuad(kTributaryAreaPoints)) {
      const shape::SurfaceShape<double> shape = shape::surfaceShape(type, q.xi[0], q.xi[1]);
      const double dA = areaElement(type, nodes, q.xi) * q.weight;
      for (int k = 0; k < shape.count; ++k)
        area[slave.connectivity(face, k)] += shape.value[k] * dA;
    }
  }
  for (const auto& [node, nodalArea] : area) {
    PairPoint p;
    p.slaveCount = 1;
    p.slaveNodes[0] = node;
    p.slaveShape[0] = 1.0;
    p.slave.nodalArea = nodalArea;
    points.push_back(p);
  }
  return points;
}

std::vector<PairPoint> segmentToSegmentPoints(const FaceSet& slave, int integrationPoints) {
  std::vector<PairPoint> points;
  const auto rule = gaussQuad(integrationPoints);
  for (int face = 0; face < slave.connectivity.rows(); ++face) {
    for (const auto& q : rule) points.push_back(slaveSegmentPoint(slave, face, q.xi, q.weight));
  }
  return points;
}

PairPoint slaveSegmentPoint(const FaceSet& slave, int face, const Eigen::Vector2d& xi,
                            double weight) {
  const shape::SurfaceType type = segmentTypeOf(slave);
  PairPoint p;
  p.slaveFace = face;
  const shape::SurfaceShape<double> shape = shape::surfaceShape(type, xi[0], xi[1]);
  p.slaveCount = shape.count;
  for (int k = 0; k < shape.count; ++k) {
    p.slaveNodes[k] = slave.connectivity(face, k);
    p.slaveShape[k] = shape.value[k];
  }
  p.slave.segmentType = type;
  p.slave.gaussPoint = xi;
  p.slave.gaussWeight = weight;
  return p;
}

std::vector<PairPoint> segmentToAnalyticalPoints(const FaceSet& master, int integrationPoints) {
  std::vector<PairPoint> points;
  const auto rule = gaussQuad(integrationPoints);
  for (int face = 0; face < master.connectivity.rows(); ++face) {
    for (const auto& q : rule) {
      PairPoint p;
      p.fixedSegment = p.segment = face;
      p.gaussPoint = p.xi = q.xi;
      p.gaussWeight = q.weight;
      points.push_back(p);
    }
  }
  return points;
}

Eigen::Vector3d slavePosition(const PairPoint& point, const Eigen::Matrix3Xd& x) {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  for (int a = 0; a < point.slaveCount; ++a)
    position += point.slaveShape[a] * x.col(point.slaveNodes[a]);
  return position;
}

PointTrial trialOf(const PointEvaluation& e, const LawParameters& law) {
  PointTrial t;
  t.valid = e.valid;
  if (!e.valid) return t;
  const auto& kin = e.kinematics;
  t.xi = e.xi;
  t.slavePoint = kin.slavePoint;
  t.masterPoint = kin.frame.rho;
  t.normal = kin.frame.normal;
  t.gap = kin.gap;
  t.weight = kin.weight;
  t.state = e.response.state;
  t.normalTraction = e.response.normal;
  if (e.response.state != ContactState::Open && e.response.frictional) {
    t.traction = e.response.tangential.vector;
    t.tractionCovariant = e.response.tangential.covariant;
    // Lambda_T = (T^tr_i + eps_T Delta rho . rho_i) rho^i: the trial before the increment.
    for (int i = 0; i < 2; ++i) {
      t.tractionBase += (e.response.tangential.trialCovariant[i] +
                         law.penaltyTangential * kin.slip.dot(kin.frame.rhoCov[i])) *
                        kin.frame.rhoContra[i];
    }
    if (e.response.state == ContactState::Slip && law.penaltyTangential > 0) {
      // Slip of this step: the part of the trial traction the return mapping removed.
      t.slipIncrement =
          (e.response.tangential.trialNorm - law.friction * std::abs(t.normalTraction)) /
          law.penaltyTangential;
    }
  }
  return t;
}

// Force on the slave body: the opposite of the internal-force contribution.
Eigen::Vector3d slaveSideForce(const PointTrial& t) {
  if (t.state == ContactState::Open) return Eigen::Vector3d::Zero();
  return (-t.normalTraction * t.normal + t.traction) * t.weight;
}

ContactPairRecord pairRecord(const std::string& name, const std::vector<PairPoint>& points) {
  ContactPairRecord r;
  r.name = name;
  const int n = static_cast<int>(points.size());
  r.position.resize(3, n);
  r.gap.resize(n);
  r.normalTraction.resize(n);
  r.tangentialTraction.resize(3, n);
  r.state.resize(n);
  r.slipIncrement.resize(n);
  r.accumulatedSlip.resize(n);
  r.weight.resize(n);
  r.edgeShare.resize(n);
  std::map<int, Eigen::Vector3d> nodalForce;  // physical force on the slave side
  for (int i = 0; i < n; ++i) {
    const PairPoint& p = points[i];
    const PointTrial& t = p.trial;
    r.position.col(i) = t.slavePoint;
    r.gap[i] = t.valid ? t.gap : std::numeric_limits<double>::quiet_NaN();
    r.normalTraction[i] = t.normalTraction;
    r.tangentialTraction.col(i) = t.traction;
    r.state[i] = static_cast<int>(t.state);
    r.slipIncrement[i] = t.slipIncrement;
    r.accumulatedSlip[i] = p.committed.accumulatedSlip;
    r.weight[i] = t.weight;
    r.edgeShare[i] = t.valid ? freeEdgeFactor(t.xi, p.layout.freeEdges) : 1.0;
    const Eigen::Vector3d force = slaveSideForce(t);
    r.totalForce += force;
    for (int a = 0; a < p.slaveCount; ++a) {
      auto [it, inserted] = nodalForce.try_emplace(p.slaveNodes[a], Eigen::Vector3d::Zero());
      it->second += p.slaveShape[a] * force;
    }
  }
  r.slaveNodes.reserve(nodalForce.size());
  r.slaveNodalForce.resize(3, static_cast<int>(nodalForce.size()));
  int column = 0;
  for (const auto& [node, force] : nodalForce) {
    r.slaveNodes.push_back(node);
    r.slaveNodalForce.col(column++) = force;
  }
  return r;
}

}  // namespace cc::contact
