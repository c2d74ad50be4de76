// Contact pair diagnostics: how many points changed their state (open/stick/slip) or master
// segment between two Newton iterations, and how many are in contact. A residual whose active
// set keeps changing is not smooth, and Newton cannot converge quadratically through it
// (issue 14; `covcontact run --newton-log` prints it per iteration). The signature of the active
// set lets Newton see the set return to an earlier iteration's (a cycle). Per point, the changes
// since the last commit or restore name the points that keep a failed solve switching, and tell
// a line-search trial's first crossings of master edges from crossings back (hops). The
// deepest penetration of the converged steps under the master (not beside its free edges),
// against the depth of the elements behind the surface, tells a penalty too soft for the mesh.
#include <fmt/format.h>

#include <algorithm>

#include "contact/contact_pair.hpp"
#include "contact/contact_point.hpp"

namespace cc::contact {

namespace {

// A penetration beyond this share of the element layer's depth is reported. The automatic
// penalty aims at about a tenth (model/automatic_penalty.hpp; ANSYS's default penetration
// tolerance is also a tenth of the underlying element's depth). On the ironing slab refined
// 1.5 times at the decks' eps = 20 the penetration at its free side edges reached a third of
// the depth and those elements folded, the die force 14 % low; the decks' own mesh reaches
// 17 % and runs well (docs/verification/sliding.md, report).
constexpr double kPenetrationWarningShare = 0.25;

// A point's state at its last evaluation (open without a valid trial), and its master segment
// while in contact (-1 when open): what takeChanges() counts and pendingCrossings() compares.
ContactState evaluatedState(const PairPoint& point) {
  return point.trial.valid ? point.trial.state : ContactState::Open;
}
int segmentInContact(const PairPoint& point) {
  return evaluatedState(point) != ContactState::Open ? point.segment : -1;
}

}  // namespace

void ContactPair::watchPenetration() {
  for (const PairPoint& point : points_) {
    const PointHistory& history = point.committed;
    if (history.state == ContactState::Open || history.gap == kNoGap) continue;
    // A point beyond a free edge of the master (edge=fade's band, contact_point.hpp) lies beside
    // the master body, not in it: its gap is measured to the segment's extension, and its force
    // fades by design. Counted, the slab's side nodes beside a die as wide as the slab made the
    // run report 93 % of the element depth and ask for a stiffer penalty, where the points under
    // the die reached 11 % (ironing_nts_mu03_equal, predictor=extrapolate; docs/verification/
    // sliding.md, thirty-ninth session).
    if (freeEdgeFactor(history.xi, point.layout.freeEdges) < 1) continue;
    if (-history.gap > deepestPenetration_) {
      deepestPenetration_ = -history.gap;
      deepestPenetrationTime_ = gapTime_;
    }
  }
}

std::string ContactPair::penetrationWarning() const {
  const double depth = config_.layerDepth;
  if (!(depth > 0) || deepestPenetration_ <= kPenetrationWarningShare * depth) return {};
  const std::string automatic =
      config_.referencePenalty > 0
          ? fmt::format(" (the automatic penalty for this mesh, 10 E/h: {:.3g})",
                        config_.referencePenalty)
          : "";
  return fmt::format(
      "contact '{}': the penetration reached {:.3g} at t = {:.6g}, {:.0f} % of the depth of the "
      "elements behind the softer surface ({:.3g}); a penalty this soft for the mesh changes "
      "the results and can fold the elements at the contact's edges: raise eps_n and eps_t{} "
      "or use enforcement=augmented",
      config_.name, deepestPenetration_, deepestPenetrationTime_, 100 * deepestPenetration_ / depth,
      depth, automatic);
}

ContactChanges ContactPair::takeChanges() {
  countedState_.resize(points_.size(), ContactState::Open);
  countedSegment_.resize(points_.size(), -1);
  stateChangesInAttempt_.resize(points_.size(), 0);
  segmentChangesInAttempt_.resize(points_.size(), 0);
  ContactChanges changes;
  changes.signature = 0xcbf29ce484222325ULL;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const PairPoint& point = points_[i];
    if (!evaluatedThisPass(point)) continue;  // another process evaluates it
    const ContactState state = evaluatedState(point);
    const int segment = segmentInContact(point);
    if (state != countedState_[i]) {
      ++changes.state;
      ++stateChangesInAttempt_[i];
    }
    // A segment change counts only for a point in contact before and after.
    if (segment >= 0 && countedSegment_[i] >= 0 && segment != countedSegment_[i]) {
      ++changes.segment;
      ++segmentChangesInAttempt_[i];
    }
    if (state != ContactState::Open) {
      ++changes.active;
      // FNV-1a over (point, state, segment) of the points in contact.
      for (const std::uint64_t word :
           {std::uint64_t(i), std::uint64_t(state), std::uint64_t(std::int64_t(segment))}) {
        changes.signature = (changes.signature ^ word) * 0x100000001b3ULL;
      }
    }
    countedState_[i] = state;
    countedSegment_[i] = segment;
  }
  return changes;
}

PendingCrossings ContactPair::pendingCrossings() const {
  PendingCrossings pending;
  for (std::size_t i = 0; i < points_.size() && i < countedSegment_.size(); ++i) {
    // As takeChanges() counts a segment change: in contact before and after.
    if (!evaluatedThisPass(points_[i])) continue;
    const int segment = segmentInContact(points_[i]);
    if (segment < 0 || countedSegment_[i] < 0 || segment == countedSegment_[i]) continue;
    ++(segmentChangesInAttempt_[i] == 0 ? pending.first : pending.repeated);
  }
  return pending;
}

void ContactPair::forgetChangesInAttempt() {
  std::fill(stateChangesInAttempt_.begin(), stateChangesInAttempt_.end(), 0);
  std::fill(segmentChangesInAttempt_.begin(), segmentChangesInAttempt_.end(), 0);
}

int ContactPair::nearestNode(std::size_t item) const {
  const PairPoint& point = points_[item];
  if (point.slaveCount == 0) {
    return point.layout.masterCount > 0
               ? point.nodes[static_cast<std::size_t>(point.layout.masterLocal[0])]
               : -1;
  }
  const auto shape = point.slaveShape.begin();
  const auto largest = std::max_element(shape, shape + point.slaveCount);
  return point.slaveNodes[static_cast<std::size_t>(largest - shape)];
}

}  // namespace cc::contact
