// Contact pair: item evaluation, history initialisation, commit and restore.
#include "contact/contact_pair.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "contact/tangent_parts.hpp"

namespace cc::contact {

namespace {

// Relative asymmetry below which an exact point tangent counts as symmetric.
constexpr double kSymmetryTolerance = 1e-12;

}  // namespace

ContactPair::ContactPair(ContactPairConfig config, const FaceSet& master,
                         std::vector<PairPoint> points)
    : config_(std::move(config)),
      builtPenaltyNormal_(config_.law.penaltyNormal),
      builtPenaltyTangential_(config_.law.penaltyTangential),
      tracker_(master),
      points_(std::move(points)),
      accelerator_(config_.accelerationDepth) {
  tracker_.setSmooth(config_.smoothMaster);
  tracker_.setCreaseAngle(config_.creaseAngle);
  tracker_.setFadingEdges(config_.fadingEdges);
  for (PairPoint& p : points_) buildItem(p);
}

std::unique_ptr<ContactPair> ContactPair::nodeToSegment(ContactPairConfig config, const Mesh& mesh,
                                                        const FaceSet& master,
                                                        const FaceSet& slave) {
  return std::unique_ptr<ContactPair>(
      new ContactPair(std::move(config), master, nodeToSegmentPoints(mesh, slave)));
}

std::unique_ptr<ContactPair> ContactPair::segmentToSegment(ContactPairConfig config,
                                                           const FaceSet& master,
                                                           const FaceSet& slave) {
  // With integration=segments these Gauss points stand in until the first prepare() segments.
  std::vector<PairPoint> points = segmentToSegmentPoints(slave, config.integrationPoints);
  std::unique_ptr<ContactPair> pair(new ContactPair(std::move(config), master, std::move(points)));
  if (pair->config_.segmentIntegration) pair->slaveFaces_ = slave;
  return pair;
}

std::unique_ptr<ContactPair> ContactPair::segmentToAnalytical(ContactPairConfig config,
                                                              const FaceSet& master,
                                                              RigidSurface surface,
                                                              SurfaceMotion motion) {
  std::vector<PairPoint> points = segmentToAnalyticalPoints(master, config.integrationPoints);
  std::unique_ptr<ContactPair> pair(new ContactPair(std::move(config), master, std::move(points)));
  pair->surface_ = surface;
  pair->motion_ = std::move(motion);
  return pair;
}

// The item's node list: slave nodes, the current master segment's nodes, and the nodes of the
// segment of the last converged projection when that differs (eq. (47) needs it).
void ContactPair::buildItem(PairPoint& point) const {
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
  layout.masterType = master().type();
  if (point.segment >= 0) {
    layout.masterCount = master().nodesPerSegment();
    for (int k = 0; k < layout.masterCount; ++k) {
      layout.masterLocal[k] = localIndex(master().node(point.segment, k));
    }
    if (searchesMasterSegments(config_.kind) && config_.fadingEdges) {
      for (int e = 0; e < 4; ++e) {
        if (master().neighbour(point.segment, e) < 0) layout.freeEdges |= 1u << e;
      }
    }
  }
  const int previous = point.committed.projected ? point.committed.segment : -1;
  if (searchesMasterSegments(config_.kind) && previous >= 0 && previous != point.segment) {
    layout.previousMasterType = master().type();
    layout.previousMasterCount = master().nodesPerSegment();
    for (int k = 0; k < layout.previousMasterCount; ++k) {
      layout.previousMasterLocal[k] = localIndex(master().node(previous, k));
    }
  }
  layout.nodeCount = static_cast<int>(point.nodes.size());
}

LocalStatus ContactPair::searchSegments(const Eigen::Matrix3Xd& x, double time) {
  const LocalStatus status = tracker_.track(points_, x, time, config_.name, moved_);
  for (int i : moved_) buildItem(points_[i]);
  if (!moved_.empty()) ++topologyVersion_;
  return status;
}

void ContactPair::initializeHistory(const AssemblyState& state) {
  const Eigen::Matrix3Xd& x = *state.previous;
  if (!searchesMasterSegments(config_.kind)) {
    const Eigen::Vector3d offset = motion_ ? motion_(state.previousTime) : Eigen::Vector3d::Zero();
    for (PairPoint& point : points_) {
      const NodeMatrix<double> nodes = master().segmentNodes(point.fixedSegment, x);
      const shape::SurfaceShape<double> shape =
          shape::surfaceShape(master().type(), point.gaussPoint[0], point.gaussPoint[1]);
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
    for (PairPoint& point : points_) {
      point.committed.projected = point.segment >= 0;
      point.committed.segment = point.segment;
      point.committed.xi = point.xi;
    }
  }
  for (PairPoint& point : points_) {
    point.committedSearchSegment = point.segment;
    point.committedSearchXi = point.xi;
    point.segmentChangesInStep = 0;
    buildItem(point);
  }
  ++topologyVersion_;
  historyInitialized_ = true;
}

LocalStatus ContactPair::prepare(const AssemblyState& state) {
  ++evaluationPass_;
  preparedTime_ = state.time;
  if (config_.smoothMaster && (!normalsReady_ || normalsTime_ != state.previousTime)) {
    // Normals from the converged configuration at the step's start, fixed over the step (a
    // cut-back retries from the same one): they keep an item's node list the segment's nodes,
    // and the tangent is exact for this choice (beyond_the_paper.md).
    tracker_.updateNormals(*state.previous);
    normalsTime_ = state.previousTime;
    normalsReady_ = true;
  }
  if (config_.segmentIntegration && (!segmentsReady_ || segmentsTime_ != state.previousTime)) {
    // Once per step (a cut-back retries with the same points): within a Newton solve the
    // points stay put, so the residual is as smooth as with Gauss points and the tangent stays
    // its consistent linearization (docs/verification/segment_sts.md).
    const LocalStatus status = resegment(state);
    if (!status.ok) return status;
  }
  if (!historyInitialized_) initializeHistory(state);
  if (!searchesMasterSegments(config_.kind)) {
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

PointSetup ContactPair::setupFor(const PairPoint& point) const {
  PointSetup setup;
  setup.kind = config_.kind;
  setup.layout = point.layout;
  setup.slave = point.slave;
  setup.history = point.committed;
  setup.history.stepStart = evaluationPass_ == passAtStepStart_ + 1;
  setup.law = config_.law;
  if (config_.augmented) {
    setup.history.multiplierNormal = point.multiplierNormal;
    setup.history.tractionAugmentation = point.tractionAugmentation;
  }
  if (config_.smoothMaster && point.segment >= 0) {
    setup.layout.smoothMaster = true;
    setup.layout.masterNormals = master().segmentNormals(point.segment);
    if (point.layout.previousMasterCount > 0) {
      setup.layout.previousMasterNormals = master().segmentNormals(point.committed.segment);
    }
  }
  setup.parameter = point.xi;
  setup.gaussWeight = point.gaussWeight;
  setup.surface = &surface_;
  setup.surfaceOffset = surfaceOffset_;
  return setup;
}

LocalStatus ContactPair::evaluate(std::size_t item, const AssemblyState& state,
                                  Eigen::VectorXd& force, Eigen::MatrixXd* tangent) {
  PairPoint& point = points_[item];
  point.evaluatedInPass = evaluationPass_;
  if (point.layout.masterCount == 0) {  // no master segment under this point: open
    point.trial = PointTrial{};
    return LocalStatus::success();
  }
  NodeMatrix<double> nodes(3, point.layout.nodeCount);
  for (int k = 0; k < point.layout.nodeCount; ++k)
    nodes.col(k) = state.current->col(point.nodes[k]);
  PointSetup setup = setupFor(point);
  setup.history.heldClosed = holdsClosedAtPrediction(setup.history, state);
  if (predictsSurfaceMotion(setup, state))
    return evaluateSurfaceMotionPredictor(point, setup, state, nodes, force, tangent);
  return evaluateExactly(point, setup, nodes, force, tangent);
}

LocalStatus ContactPair::evaluateExactly(PairPoint& point, const PointSetup& setup,
                                         const NodeMatrix<double>& nodes, Eigen::VectorXd& force,
                                         Eigen::MatrixXd* tangent) {
  const std::size_t item = static_cast<std::size_t>(&point - points_.data());
  const PointEvaluation e = evaluatePoint(setup, nodes);
  point.trial = trialOf(e, config_.law);
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

// Newton's extrapolating predictor moves every node by the last step's motion, which is exact
// only to first order: where the bodies' surfaces are curved and slide past each other, the
// gap at the predicted iterate is off by about the gap's curvature times the squared step (on
// the stiff ball of issue 14, 0.05 of slide over a radius of 3: 4e-4, against a penetration of
// 7e-4 under eps_N = 50 E / h). Points under a stiff penalty then open at the predicted iterate
// and close again at the next, and the first Newton update is computed for the wrong active
// set. The gap itself varies smoothly from step to step while the point stays in contact, so a
// point closed at the last two converged steps whose gap, extrapolated over this step like the
// displacements, stays closed (g_n + r (g_n - g_(n-1)) < 0, r = dt / dt_prev) keeps the penalty
// branch N = eps_N g at the predicted iterate even where the predicted configuration opens it.
// From the second iterate on the law is the paper's again, so a converged step is unchanged;
// only Newton's path differs (docs/verification/sliding.md, twenty-second session). Not in
// the retry of a failed step (the safety net keeps the paper's law at every iterate), not
// with the augmented Lagrangian (its multipliers decide its active set) and not with
// integration=segments (its points are made anew every step, so they have no gap history).
bool ContactPair::holdsClosedAtPrediction(const PointHistory& history,
                                          const AssemblyState& state) const {
  if (!history.stepStart || !state.extrapolatedStart || config_.augmented || retryingStep_ ||
      config_.segmentIntegration) {
    return false;
  }
  if (history.state == ContactState::Open || !(history.previousGap <= 0)) return false;
  const double previousStep = gapTime_ - previousGapTime_;
  if (!(previousStep > 0)) return false;
  const double ratio = (state.time - gapTime_) / previousStep;
  return history.gap + ratio * (history.gap - history.previousGap) < 0;
}

bool ContactPair::predictsSurfaceMotion(const PointSetup& setup, const AssemblyState& state) const {
  return setup.kind == PointKind::SegmentToAnalytical && setup.history.stepStart && motion_ &&
         !state.extrapolatedStart;
}

// STAS, the step's first iterate: the rigid surface's motion over the step enters linearly, as a
// meshed die's prescribed motion enters the first Newton iteration through its stiffness. The
// point is evaluated with the surface where it was at the last converged step (offset s_n); the
// force depends on the item's nodes only relative to the surface, so
// f(x, s_n+1) = f(x - ds, s_n) ~ f(x, s_n) - K(x, s_n) ds, ds on every node of the item.
// Moving the surface by the whole increment at once pushed it into the slab ahead of it: on the
// ironing deck 42-48 points switched open/closed in the next iterations and plain Newton
// diverged (docs/verification/sliding.md). From the second iterate on the force is the exact
// one, so converged steps are unchanged.
LocalStatus ContactPair::evaluateSurfaceMotionPredictor(PairPoint& point, const PointSetup& setup,
                                                        const AssemblyState& state,
                                                        const NodeMatrix<double>& nodes,
                                                        Eigen::VectorXd& force,
                                                        Eigen::MatrixXd* tangent) {
  PointSetup previous = setup;
  previous.surfaceOffset = motion_(state.previousTime);
  const Eigen::Vector3d increment = surfaceOffset_ - previous.surfaceOffset;
  const PointEvaluation e = evaluatePoint(previous, nodes);
  // Only a point in contact before the motion is predicted: one that the surface reaches during
  // the step has no force to extrapolate, and predicting none would let a step whose only load
  // is the surface's motion (a punch, a sphere pressed in) look converged at its first iterate.
  if (!e.valid || e.response.state == ContactState::Open)
    return evaluateExactly(point, setup, nodes, force, tangent);
  point.trial = trialOf(e, config_.law);
  Eigen::MatrixXd local;
  Eigen::MatrixXd& K = tangent ? *tangent : local;
  pointTangent(previous, nodes, e, config_.tangentMode, config_.parts, K);
  Eigen::VectorXd shift(3 * point.layout.nodeCount);
  for (int k = 0; k < point.layout.nodeCount; ++k) shift.segment<3>(3 * k) = increment;
  force = e.force - K * shift;
  point.trial.symmetric = (K - K.transpose()).norm() <= kSymmetryTolerance * K.norm();
  if (!force.allFinite() || !K.allFinite()) {
    return LocalStatus::failure(
        FailureKind::NotFinite,
        fmt::format("contact pair '{}', point {}: predicted force or tangent is not finite",
                    config_.name, &point - points_.data()));
  }
  return LocalStatus::success();
}

bool ContactPair::tangentSymmetric() const {
  return std::all_of(points_.begin(), points_.end(), [this](const PairPoint& p) {
    return !evaluatedThisPass(p) || p.trial.symmetric;
  });
}

void ContactPair::commitStep() {
  accountDissipation();
  commitAugmentation();
  for (PairPoint& point : points_) {
    PointHistory& h = point.committed;
    const PointTrial& t = point.trial;
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
    h.previousGap = h.gap;
    h.gap = t.valid ? t.gap : kNoGap;
    point.committedSearchSegment = point.segment;
    point.committedSearchXi = point.xi;
    point.segmentChangesInStep = 0;
  }
  passAtStepStart_ = evaluationPass_;
  retryingStep_ = false;
  previousGapTime_ = gapTime_;
  gapTime_ = preparedTime_;
  rememberedSearch_.clear();
  forgetChangesInAttempt();
  watchPenetration();
  // The previous-segment nodes of the items follow the new history.
  for (PairPoint& point : points_) buildItem(point);
  ++topologyVersion_;
}

void ContactPair::restoreStep() {
  passAtStepStart_ = evaluationPass_;
  retryingStep_ = true;
  rememberedSearch_.clear();
  forgetChangesInAttempt();
  restoreAugmentation();
  for (PairPoint& point : points_) {
    if (searchesMasterSegments(config_.kind)) {
      point.segment = point.committedSearchSegment;
      point.xi = point.committedSearchXi;
      point.segmentChangesInStep = 0;
    }
    point.trial = PointTrial{};
    buildItem(point);
  }
  tracker_.invalidateGrid();
  ++topologyVersion_;
}

void ContactPair::rememberSearch() {
  rememberedSearch_.resize(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const PairPoint& point = points_[i];
    rememberedSearch_[i] = {point.segment, point.xi, point.segmentChangesInStep};
  }
}

void ContactPair::recallSearch() {
  if (rememberedSearch_.size() != points_.size()) return;
  bool rebuilt = false;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    PairPoint& point = points_[i];
    const SearchPosition& remembered = rememberedSearch_[i];
    point.xi = remembered.xi;
    point.segmentChangesInStep = remembered.segmentChangesInStep;
    if (point.segment != remembered.segment) {
      point.segment = remembered.segment;
      buildItem(point);
      rebuilt = true;
    }
  }
  if (rebuilt) ++topologyVersion_;
}

ContactPairRecord ContactPair::record() const {
  ContactPairRecord r = pairRecord(config_.name, points_);
  r.stepDissipation.resize(pointCount());
  for (int i = 0; i < pointCount(); ++i) r.stepDissipation[i] = pointDissipation(points_[i].trial);
  r.penaltyNormal = config_.law.penaltyNormal;
  r.penaltyTangential = config_.law.penaltyTangential;
  r.automaticPenalty = config_.automaticPenalty;
  r.penaltyEnergy = penaltyEnergy();
  r.dissipation = stepDissipation_;
  r.dissipatedEnergy = dissipatedEnergy_;
  return r;
}

double ContactPair::penaltyRatio() const {
  if (!(config_.referencePenalty > 0)) return 0;
  return std::max(builtPenaltyNormal_, builtPenaltyTangential_) / config_.referencePenalty;
}

void ContactPair::scalePenalties(double factor) {
  // Never below the automatic penalty: in a model whose other pair is far stiffer, this pair
  // keeps its own penalty (or eps_ref) instead of losing its contact for the soft solves.
  const double ratio = penaltyRatio();
  const double own = ratio > 0 ? std::max(factor, std::min(1.0, 1.0 / ratio)) : 1.0;
  config_.law.penaltyNormal = own * builtPenaltyNormal_;
  config_.law.penaltyTangential = own * builtPenaltyTangential_;
}

}  // namespace cc::contact
