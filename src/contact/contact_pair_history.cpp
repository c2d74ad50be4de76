// Restart support of ContactPair: the committed point history (PointHistory) and the search
// state (segment, xi) as a plain table, so that a continued run starts every point exactly where
// the interrupted one left it after its last commit.
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "contact/contact_pair.hpp"

namespace cc::contact {

namespace {

// Rows of the history table, one column per point. Integers and flags are stored as doubles
// (exact for these magnitudes).
enum HistoryRow : int {
  kProjected = 0,
  kSegment = 1,
  kXi = 2,                 // 2 rows
  kTraction = 4,           // 3 rows, T^(n) Cartesian
  kTractionCovariant = 7,  // 2 rows, T_i^(n)
  kMasterPoint = 9,        // 3 rows (STAS)
  kSurfaceOffset = 12,     // 3 rows (STAS)
  kState = 15,
  kAccumulatedSlip = 16,
  kSearchSegment = 17,  // the segment the next search walk starts from
  kSearchXi = 18,       // 2 rows, its parameter
  // Augmented Lagrangian: the committed normal multiplier, the next step's first guess, and the
  // pair's penalties, which aug_grow may have raised (the same in every column). Tables written
  // before these rows existed have kLegacyRowCount rows: multipliers 0, the deck's penalties.
  kMultiplierNormal = 20,
  kPenaltyNormal = 21,
  kPenaltyTangential = 22,
  // The gap history (g_n, g_(n-1), kNoGap without a projection) and the times of those two commits
  // (the same in every column), from which an extrapolated first iterate predicts the point's
  // state (ContactPair::holdsClosedAtPrediction). Tables written before these rows existed
  // have kRowCountBeforeGaps rows: no gap history, so no point is held in the first two steps.
  kGap = 23,
  kPreviousGap = 24,
  kGapTime = 25,
  kPreviousGapTime = 26,
  // The deepest penetration of the converged steps and its time (the same in every column), so
  // that a continued run's warning (ContactPair::penetrationWarning) covers the steps before the
  // restart. Tables written before these rows existed have kRowCountBeforePenetration rows: the
  // watch starts again at the restart.
  kDeepestPenetration = 27,
  kDeepestPenetrationTime = 28,
  kRowCount = 29,
  kLegacyRowCount = 20,
  kRowCountBeforeGaps = 23,
  kRowCountBeforePenetration = 27,
};
static_assert(kRowCount == ContactPair::kHistoryRows);

ContactState stateFrom(double value, const std::string& pair, int point) {
  const int state = static_cast<int>(value);
  if (state != value || state < static_cast<int>(ContactState::Open) ||
      state > static_cast<int>(ContactState::Slip)) {
    throw std::invalid_argument(fmt::format(
        "contact pair '{}', point {}: invalid state {} in the history", pair, point, value));
  }
  return static_cast<ContactState>(state);
}

}  // namespace

Eigen::MatrixXd ContactPair::exportHistory() const {
  Eigen::MatrixXd table(kHistoryRows, pointCount());
  for (int i = 0; i < pointCount(); ++i) {
    const PairPoint& point = points_[i];
    const PointHistory& h = point.committed;
    auto column = table.col(i);
    column[kProjected] = h.projected ? 1 : 0;
    column[kSegment] = h.segment;
    column.segment<2>(kXi) = h.xi;
    column.segment<3>(kTraction) = h.traction;
    column.segment<2>(kTractionCovariant) = h.tractionCovariant;
    column.segment<3>(kMasterPoint) = h.masterPoint;
    column.segment<3>(kSurfaceOffset) = h.surfaceOffset;
    column[kState] = static_cast<int>(h.state);
    column[kAccumulatedSlip] = h.accumulatedSlip;
    column[kSearchSegment] = point.segment;
    column.segment<2>(kSearchXi) = point.xi;
    column[kMultiplierNormal] = point.committedMultiplierNormal;
    column[kPenaltyNormal] = builtPenaltyNormal_;
    column[kPenaltyTangential] = builtPenaltyTangential_;
    column[kGap] = h.gap;
    column[kPreviousGap] = h.previousGap;
    column[kGapTime] = gapTime_;
    column[kPreviousGapTime] = previousGapTime_;
    column[kDeepestPenetration] = deepestPenetration_;
    column[kDeepestPenetrationTime] = deepestPenetrationTime_;
  }
  return table;
}

// Which rows a stored history table holds: tables written by earlier versions lack the rows
// added since (HistoryRow). Throws std::invalid_argument for a table that fits no version.
ContactPair::HistoryLayout ContactPair::historyLayout(const Eigen::MatrixXd& table) const {
  HistoryLayout layout;
  layout.legacy = table.rows() == kLegacyRowCount;
  layout.withPenetration = table.rows() == kHistoryRows;
  layout.withGaps = layout.withPenetration || table.rows() == kRowCountBeforePenetration;
  if ((!layout.withGaps && !layout.legacy && table.rows() != kRowCountBeforeGaps) ||
      table.cols() != pointCount()) {
    throw std::invalid_argument(fmt::format(
        "contact pair '{}': history table is {} x {}, expected {} x {} (one column per point)",
        config_.name, table.rows(), table.cols(), kHistoryRows, pointCount()));
  }
  return layout;
}

void ContactPair::importHistory(const Eigen::MatrixXd& table) {
  if (config_.segmentIntegration) {
    // The points of integration=segments depend on the configuration they were segmented at,
    // which the restart data do not hold (docs/verification/segment_sts.md).
    throw std::invalid_argument(fmt::format(
        "contact pair '{}': a run with integration=segments cannot be restarted (its points "
        "are rebuilt every step); rerun it from the start",
        config_.name));
  }
  const HistoryLayout layout = historyLayout(table);
  if (!layout.legacy) importAugmentation(table);
  for (int i = 0; i < pointCount(); ++i) importPointHistory(i, table.col(i), layout.withGaps);
  gapTime_ = layout.withGaps && pointCount() > 0 ? table(kGapTime, 0) : 0.0;
  previousGapTime_ = layout.withGaps && pointCount() > 0 ? table(kPreviousGapTime, 0) : 0.0;
  importDeepestPenetration(layout.withPenetration ? table : Eigen::MatrixXd());
  // The history replaces the initial projection (Table 1, step 1), and the search grid and the
  // item topology follow the restored segments.
  historyInitialized_ = true;
  tracker_.invalidateGrid();
  ++topologyVersion_;
}

// Point i's committed history and search state from its column; its trial state starts afresh.
void ContactPair::importPointHistory(int i, const Eigen::Ref<const Eigen::VectorXd>& column,
                                     bool withGaps) {
  const bool segmentBased = searchesMasterSegments(config_.kind);
  for (int row : {kSegment, kSearchSegment}) {
    const double segment = column[row];
    if (segmentBased && (segment != static_cast<int>(segment) || segment < -1 ||
                         segment >= master().segmentCount())) {
      throw std::invalid_argument(
          fmt::format("contact pair '{}', point {}: master segment {} does not exist", config_.name,
                      i, segment));
    }
  }
  PairPoint& point = points_[i];
  PointHistory& h = point.committed;
  h.projected = column[kProjected] != 0;
  h.segment = static_cast<int>(column[kSegment]);
  h.xi = column.segment<2>(kXi);
  h.traction = column.segment<3>(kTraction);
  h.tractionCovariant = column.segment<2>(kTractionCovariant);
  h.masterPoint = column.segment<3>(kMasterPoint);
  h.surfaceOffset = column.segment<3>(kSurfaceOffset);
  h.state = stateFrom(column[kState], config_.name, i);
  h.accumulatedSlip = column[kAccumulatedSlip];
  h.gap = withGaps ? column[kGap] : kNoGap;
  h.previousGap = withGaps ? column[kPreviousGap] : kNoGap;
  if (segmentBased) point.segment = static_cast<int>(column[kSearchSegment]);
  point.xi = column.segment<2>(kSearchXi);
  point.committedSearchSegment = point.segment;
  point.committedSearchXi = point.xi;
  point.segmentChangesInStep = 0;
  point.trial = PointTrial{};
  buildItem(point);
}

// The rows of the penetration watch (an empty table: none stored, the watch starts afresh).
void ContactPair::importDeepestPenetration(const Eigen::MatrixXd& table) {
  deepestPenetration_ = deepestPenetrationTime_ = 0;
  if (table.cols() == 0) return;
  const double depth = table(kDeepestPenetration, 0), time = table(kDeepestPenetrationTime, 0);
  if (!(depth >= 0) || !std::isfinite(depth) || !std::isfinite(time)) {
    throw std::invalid_argument(
        fmt::format("contact pair '{}': invalid deepest penetration {} at t = {} in the history",
                    config_.name, depth, time));
  }
  deepestPenetration_ = depth;
  deepestPenetrationTime_ = time;
}

// The rows of the augmented Lagrangian (kMultiplierNormal ...): a restarted run continues with the
// multipliers and penalties the interrupted one had, so that it ends where that one ended.
void ContactPair::importAugmentation(const Eigen::MatrixXd& table) {
  for (int i = 0; i < pointCount(); ++i) {
    const double multiplier = table(kMultiplierNormal, i);
    if (!std::isfinite(multiplier) || multiplier > 0) {
      throw std::invalid_argument(
          fmt::format("contact pair '{}', point {}: invalid normal multiplier {} in the history "
                      "(a finite value <= 0 expected)",
                      config_.name, i, multiplier));
    }
    points_[i].committedMultiplierNormal = multiplier;
    points_[i].multiplierNormal = multiplier;
  }
  // Only aug_grow changes a pair's penalties, and only upwards: a stored penalty below the deck's
  // means the deck was edited before the restart, and the deck's then stands.
  if (pointCount() == 0 || !config_.augmented || !config_.growPenalty) return;
  const double normal = table(kPenaltyNormal, 0), tangential = table(kPenaltyTangential, 0);
  if (!(normal > 0) || !std::isfinite(normal) || !(tangential >= 0) || !std::isfinite(tangential)) {
    throw std::invalid_argument(
        fmt::format("contact pair '{}': invalid penalties eps_n = {}, eps_t = {} in the history",
                    config_.name, normal, tangential));
  }
  if (normal < builtPenaltyNormal_ || tangential < builtPenaltyTangential_) return;
  builtPenaltyNormal_ = config_.law.penaltyNormal = normal;
  builtPenaltyTangential_ = config_.law.penaltyTangential = tangential;
}

}  // namespace cc::contact
