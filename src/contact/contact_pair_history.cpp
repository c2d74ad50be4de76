// Restart support of ContactPair: the committed point history (PointHistory) and the search
// state (segment, xi) as a plain table, so that a continued run starts every point exactly where
// the interrupted one left it after its last commit.
#include <fmt/format.h>

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
  kRowCount = 20,
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
  }
  return table;
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
  if (table.rows() != kHistoryRows || table.cols() != pointCount()) {
    throw std::invalid_argument(fmt::format(
        "contact pair '{}': history table is {} x {}, expected {} x {} (one column per point)",
        config_.name, table.rows(), table.cols(), kHistoryRows, pointCount()));
  }
  const bool segmentBased = searchesMasterSegments(config_.kind);
  for (int i = 0; i < pointCount(); ++i) {
    const auto column = table.col(i);
    for (int row : {kSegment, kSearchSegment}) {
      const double segment = column[row];
      if (segmentBased && (segment != static_cast<int>(segment) || segment < -1 ||
                           segment >= master().segmentCount())) {
        throw std::invalid_argument(
            fmt::format("contact pair '{}', point {}: master segment {} does not exist",
                        config_.name, i, segment));
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
    if (segmentBased) point.segment = static_cast<int>(column[kSearchSegment]);
    point.xi = column.segment<2>(kSearchXi);
    point.committedSearchSegment = point.segment;
    point.committedSearchXi = point.xi;
    point.trial = PointTrial{};
    buildItem(point);
  }
  // The history replaces the initial projection (Table 1, step 1), and the search grid and the
  // item topology follow the restored segments.
  historyInitialized_ = true;
  tracker_.invalidateGrid();
  ++topologyVersion_;
}

}  // namespace cc::contact
