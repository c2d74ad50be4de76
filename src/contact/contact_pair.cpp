// Contact pair: construction of the contact points of each kind, segment search, item
// evaluation, history commit/restore and output.
#include "contact/contact_pair.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <map>

#include "contact/tangent_parts.hpp"
#include "fem/quadrature.hpp"

namespace cc::contact {

namespace {

SegmentType segmentTypeOf(const FaceSet& faces) {
  return faces.type == CellType::Quad9 ? SegmentType::Quad9 : SegmentType::Quad4;
}

// Area element |rho_1 x rho_2| of a face at xi, reference configuration.
double areaElement(SegmentType type, const NodeMatrix<double>& nodes, const Eigen::Vector2d& xi) {
  const SurfaceShape<double> shape = surfaceShape(type, xi[0], xi[1]);
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

// Relative asymmetry below which an exact point tangent counts as symmetric.
constexpr double kSymmetryTolerance = 1e-12;
// Integration rule for the NTS tributary areas (exact for the Quad9 shape functions on flat
// faces).
constexpr int kTributaryAreaPoints = 3;
// Reach of the global search, in master segment sizes: a point that lost its segment is within
// one segment of its new one (gap and slip of a step are smaller than a segment). Before this
// was relative, the first search used a reach of one length unit, which on a fine mesh put
// hundreds of segments in every grid cell (issue 8).
constexpr double kSearchReachInSegments = 1.0;

}  // namespace

ContactPair::ContactPair(ContactPairConfig config, const FaceSet& master)
    : config_(std::move(config)), master_(master) {}

std::unique_ptr<ContactPair> ContactPair::nodeToSegment(ContactPairConfig config, const Mesh& mesh,
                                                        const FaceSet& master,
                                                        const FaceSet& slave) {
  std::unique_ptr<ContactPair> pair(new ContactPair(std::move(config), master));
  // Tributary area of each slave node in the reference configuration: sum over its faces of the
  // integral of its shape function (held constant, like ds in the paper's linearization).
  std::map<int, double> area;
  const SegmentType type = segmentTypeOf(slave);
  for (int face = 0; face < slave.connectivity.rows(); ++face) {
    const NodeMatrix<double> nodes = faceNodes(slave, face, mesh.coordinates);
    for (const auto& q : gaussQuad(kTributaryAreaPoints)) {
      const SurfaceShape<double> shape = surfaceShape(type, q.xi[0], q.xi[1]);
      const double dA = areaElement(type, nodes, q.xi) * q.weight;
      for (int k = 0; k < shape.count; ++k)
        area[slave.connectivity(face, k)] += shape.value[k] * dA;
    }
  }
  for (const auto& [node, nodalArea] : area) {
    Point p;
    p.slaveCount = 1;
    p.slaveNodes[0] = node;
    p.slaveShape[0] = 1.0;
    p.slave.nodalArea = nodalArea;
    pair->points_.push_back(p);
  }
  for (Point& p : pair->points_) pair->buildItem(p);
  return pair;
}

std::unique_ptr<ContactPair> ContactPair::segmentToSegment(ContactPairConfig config,
                                                           const FaceSet& master,
                                                           const FaceSet& slave) {
  std::unique_ptr<ContactPair> pair(new ContactPair(std::move(config), master));
  const SegmentType type = segmentTypeOf(slave);
  const auto rule = gaussQuad(pair->config_.integrationPoints);
  for (int face = 0; face < slave.connectivity.rows(); ++face) {
    for (const auto& q : rule) {
      Point p;
      const SurfaceShape<double> shape = surfaceShape(type, q.xi[0], q.xi[1]);
      p.slaveCount = shape.count;
      for (int k = 0; k < shape.count; ++k) {
        p.slaveNodes[k] = slave.connectivity(face, k);
        p.slaveShape[k] = shape.value[k];
      }
      p.slave.segmentType = type;
      p.slave.gaussPoint = q.xi;
      p.slave.gaussWeight = q.weight;
      pair->points_.push_back(p);
    }
  }
  for (Point& p : pair->points_) pair->buildItem(p);
  return pair;
}

std::unique_ptr<ContactPair> ContactPair::segmentToAnalytical(ContactPairConfig config,
                                                              const FaceSet& master,
                                                              RigidSurface surface,
                                                              SurfaceMotion motion) {
  std::unique_ptr<ContactPair> pair(new ContactPair(std::move(config), master));
  pair->surface_ = surface;
  pair->motion_ = std::move(motion);
  const auto rule = gaussQuad(pair->config_.integrationPoints);
  for (int face = 0; face < master.connectivity.rows(); ++face) {
    for (const auto& q : rule) {
      Point p;
      p.fixedSegment = p.segment = face;
      p.gaussPoint = p.xi = q.xi;
      p.gaussWeight = q.weight;
      pair->points_.push_back(p);
    }
  }
  for (Point& p : pair->points_) pair->buildItem(p);
  return pair;
}

// The item's node list: slave nodes, the current master segment's nodes, and the nodes of the
// segment of the last converged projection when that differs (eq. (47) needs it).
void ContactPair::buildItem(Point& point) const {
  PointLayout& layout = point.layout;
  layout = PointLayout{};
  point.nodes.clear();
  auto localIndex = [&](int node) {
    const auto it = std::find(point.nodes.begin(), point.nodes.end(), node);
    if (it != point.nodes.end()) return static_cast<int>(it - point.nodes.begin());
    point.nodes.push_back(node);
    return static_cast<int>(point.nodes.size()) - 1;
  };
  layout.slaveCount = point.slaveCount;
  for (int a = 0; a < point.slaveCount; ++a) {
    layout.slaveLocal[a] = localIndex(point.slaveNodes[a]);
    layout.slaveShape[a] = point.slaveShape[a];
  }
  layout.masterType = master_.type();
  if (point.segment >= 0) {
    layout.masterCount = master_.nodesPerSegment();
    for (int k = 0; k < layout.masterCount; ++k) {
      layout.masterLocal[k] = localIndex(master_.node(point.segment, k));
    }
  }
  const int previous = point.committed.projected ? point.committed.segment : -1;
  if (config_.kind != PointKind::SegmentToAnalytical && previous >= 0 &&
      previous != point.segment) {
    layout.previousMasterType = master_.type();
    layout.previousMasterCount = master_.nodesPerSegment();
    for (int k = 0; k < layout.previousMasterCount; ++k) {
      layout.previousMasterLocal[k] = localIndex(master_.node(previous, k));
    }
  }
  layout.nodeCount = static_cast<int>(point.nodes.size());
}

Eigen::Vector3d ContactPair::slavePosition(const Point& point, const Eigen::Matrix3Xd& x) const {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  for (int a = 0; a < point.slaveCount; ++a)
    position += point.slaveShape[a] * x.col(point.slaveNodes[a]);
  return position;
}

LocalStatus ContactPair::searchSegments(const Eigen::Matrix3Xd& x, double time) {
  if (gridTime_ != time) {
    master_.buildSearchGrid(x, kSearchReachInSegments);
    gridTime_ = time;
  }
  bool changed = false;
  for (Point& point : points_) {
    const Eigen::Vector3d position = slavePosition(point, x);
    SegmentProjection found;
    if (point.segment >= 0) found = master_.walk(point.segment, point.xi, position, x);
    const bool brokeDownOnOwnSegment = found.projectionBrokeDown;
    if (!found.found()) found = master_.search(position, x);
    if (!found.found() && brokeDownOnOwnSegment) {
      if (changed) ++topologyVersion_;  // points before this one may have moved already
      return LocalStatus::failure(
          FailureKind::ProjectionFailure,
          fmt::format("contact pair '{}': the closest-point projection of slave point {} onto "
                      "master segment {} broke down (degenerate or strongly distorted segment)",
                      config_.name, &point - points_.data(), point.segment));
    }
    if (found.segment != point.segment) {
      point.segment = found.segment;
      buildItem(point);
      changed = true;
    }
    point.xi = found.xi;
  }
  if (changed) ++topologyVersion_;
  return LocalStatus::success();
}

void ContactPair::initializeHistory(const AssemblyState& state) {
  const Eigen::Matrix3Xd& x = *state.previous;
  if (config_.kind == PointKind::SegmentToAnalytical) {
    const Eigen::Vector3d offset = motion_ ? motion_(state.previousTime) : Eigen::Vector3d::Zero();
    for (Point& point : points_) {
      const NodeMatrix<double> nodes = master_.segmentNodes(point.fixedSegment, x);
      const SurfaceShape<double> shape =
          surfaceShape(master_.type(), point.gaussPoint[0], point.gaussPoint[1]);
      point.committed.masterPoint.setZero();
      for (int k = 0; k < shape.count; ++k)
        point.committed.masterPoint += shape.value[k] * nodes.col(k);
      point.committed.surfaceOffset = offset;
      point.committed.projected = true;
    }
  } else {
    // Before the first step no point has a segment yet, so only the global search runs and
    // the projection cannot break down on a point's own segment: this cannot fail.
    searchSegments(x, state.previousTime);
    for (Point& point : points_) {
      point.committed.projected = point.segment >= 0;
      point.committed.segment = point.segment;
      point.committed.xi = point.xi;
    }
  }
  for (Point& point : points_) {
    point.committedSearchSegment = point.segment;
    point.committedSearchXi = point.xi;
    buildItem(point);
  }
  ++topologyVersion_;
  historyInitialized_ = true;
}

LocalStatus ContactPair::prepare(const AssemblyState& state) {
  if (!historyInitialized_) initializeHistory(state);
  if (config_.kind == PointKind::SegmentToAnalytical) {
    surfaceOffset_ = motion_ ? motion_(state.time) : Eigen::Vector3d::Zero();
    if (!surfaceOffset_.allFinite()) {
      return LocalStatus::failure(FailureKind::NotFinite,
                                  fmt::format("contact pair '{}': rigid surface motion is not "
                                              "finite at t = {}",
                                              config_.name, state.time));
    }
    return LocalStatus::success();
  }
  return searchSegments(*state.current, state.time);
}

PointSetup ContactPair::setupFor(const Point& point) const {
  PointSetup setup;
  setup.kind = config_.kind;
  setup.layout = point.layout;
  setup.slave = point.slave;
  setup.history = point.committed;
  setup.law = config_.law;
  if (config_.augmented) {
    setup.history.multiplierNormal = point.multiplierNormal;
    setup.history.tractionAugmentation = point.tractionAugmentation;
  }
  setup.parameter = point.xi;
  setup.gaussWeight = point.gaussWeight;
  setup.surface = &surface_;
  setup.surfaceOffset = surfaceOffset_;
  return setup;
}

void ContactPair::storeTrial(Point& point, const PointEvaluation& e, const LawParameters& law) {
  Trial& t = point.trial;
  t = Trial{};
  t.valid = e.valid;
  if (!e.valid) return;
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
}

LocalStatus ContactPair::evaluate(std::size_t item, const AssemblyState& state,
                                  Eigen::VectorXd& force, Eigen::MatrixXd* tangent) {
  Point& point = points_[item];
  if (point.layout.masterCount == 0) {  // no master segment under this point: open
    point.trial = Trial{};
    return LocalStatus::success();
  }
  NodeMatrix<double> nodes(3, point.layout.nodeCount);
  for (int k = 0; k < point.layout.nodeCount; ++k)
    nodes.col(k) = state.current->col(point.nodes[k]);
  const PointSetup setup = setupFor(point);
  const PointEvaluation e = evaluatePoint(setup, nodes);
  storeTrial(point, e, config_.law);
  if (!e.valid) return LocalStatus::success();
  if (!e.force.allFinite()) {
    return LocalStatus::failure(
        FailureKind::NotFinite,
        fmt::format("contact pair '{}', point {}: force is not finite (gap {})", config_.name, item,
                    e.kinematics.gap));
  }
  force = e.force;
  if (tangent) {
    pointTangent(setup, nodes, e, config_.tangentMode, config_.parts, *tangent);
    if (!tangent->allFinite()) {
      return LocalStatus::failure(
          FailureKind::NotFinite,
          fmt::format("contact pair '{}', point {}: tangent is not finite", config_.name, item));
    }
    point.trial.symmetric =
        config_.tangentMode == TangentMode::Paper &&
                setup.kind != PointKind::SegmentToAnalytical  // STAS: n x m is unsymmetric
            ? contact::tangentSymmetric(e.response.state, config_.parts)
            : (*tangent - tangent->transpose()).norm() <= kSymmetryTolerance * tangent->norm();
  }
  return LocalStatus::success();
}

bool ContactPair::tangentSymmetric() const {
  return std::all_of(points_.begin(), points_.end(),
                     [](const Point& p) { return p.trial.symmetric; });
}

void ContactPair::commitStep() {
  accountDissipation();
  commitAugmentation();
  for (Point& point : points_) {
    PointHistory& h = point.committed;
    const Trial& t = point.trial;
    h.projected = t.valid;
    h.segment = point.segment;
    h.xi = t.valid ? t.xi : point.xi;
    h.traction = t.state == ContactState::Open ? Eigen::Vector3d::Zero() : t.traction;
    h.tractionCovariant =
        t.state == ContactState::Open ? Eigen::Vector2d::Zero() : t.tractionCovariant;
    h.state = t.state;
    h.accumulatedSlip += t.slipIncrement;
    h.masterPoint = t.masterPoint;
    h.surfaceOffset = surfaceOffset_;
    point.committedSearchSegment = point.segment;
    point.committedSearchXi = point.xi;
  }
  // The previous-segment nodes of the items follow the new history.
  for (Point& point : points_) buildItem(point);
  ++topologyVersion_;
}

void ContactPair::restoreStep() {
  restoreAugmentation();
  for (Point& point : points_) {
    if (config_.kind != PointKind::SegmentToAnalytical) {
      point.segment = point.committedSearchSegment;
      point.xi = point.committedSearchXi;
    }
    point.trial = Trial{};
    buildItem(point);
  }
  gridTime_ = -1;
  ++topologyVersion_;
}

ContactPairRecord ContactPair::record() const {
  ContactPairRecord r;
  r.name = config_.name;
  const int n = pointCount();
  r.position.resize(3, n);
  r.gap.resize(n);
  r.normalTraction.resize(n);
  r.tangentialTraction.resize(3, n);
  r.state.resize(n);
  r.slipIncrement.resize(n);
  r.accumulatedSlip.resize(n);
  r.weight.resize(n);
  r.stepDissipation.resize(n);
  std::map<int, Eigen::Vector3d> nodalForce;  // physical force on the slave side
  for (int i = 0; i < n; ++i) {
    const Point& p = points_[i];
    const Trial& t = p.trial;
    r.position.col(i) = t.slavePoint;
    r.gap[i] = t.valid ? t.gap : std::numeric_limits<double>::quiet_NaN();
    r.normalTraction[i] = t.normalTraction;
    r.tangentialTraction.col(i) = t.traction;
    r.state[i] = static_cast<int>(t.state);
    r.slipIncrement[i] = t.slipIncrement;
    r.accumulatedSlip[i] = p.committed.accumulatedSlip;
    r.weight[i] = t.weight;
    r.stepDissipation[i] = pointDissipation(t);
    // Force on the slave body: -(N n - T) w (the opposite of the internal-force contribution).
    const Eigen::Vector3d force =
        t.state == ContactState::Open
            ? Eigen::Vector3d::Zero()
            : Eigen::Vector3d((-t.normalTraction * t.normal + t.traction) * t.weight);
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
  r.penaltyNormal = config_.law.penaltyNormal;
  r.penaltyTangential = config_.law.penaltyTangential;
  r.automaticPenalty = config_.automaticPenalty;
  r.penaltyEnergy = penaltyEnergy();
  r.dissipation = stepDissipation_;
  r.dissipatedEnergy = dissipatedEnergy_;
  return r;
}

}  // namespace cc::contact
