// Augmented Lagrangian enforcement of a contact pair (issue 16, part 3a): Uzawa updates per load
// step. Within a Newton solve the multipliers are constants, so the paper's residual/tangent
// split and the exact tangent are unchanged; only N = min(0, lambda_N + eps_N g) and the
// traction the trial step starts from, Lambda_T = T^(n) carried to the current point plus A . rho_i
// (eq. (51) applied to the augmentation A), carry them. After a converged solve:
//   lambda_N <- N,  A <- A + (T - Lambda_T) at sticking points,
// until max over points of |N - lambda_N| and over sticking points of |T - Lambda_T| is at most
// aug_tol max |N|. For a point in contact |N - lambda_N| = eps_N |g| and for a sticking point
// |T - Lambda_T| = eps_T |Delta rho_t|: the rule bounds the penetration and the slip under
// stick by aug_tol max|N| / eps. A sliding point needs no tangential multiplier: its traction is
// mu |N| (the cone acts on the augmented N) in the direction of the trial, so Lambda_T only
// steers that direction.
// Known limit (docs/verification/augmented_lagrangian.md): on 6.1(b) in sliding, Uzawa stalls
// at an update of about 1e-3 max|N| whatever the step size, so the step fails after aug_max
// updates and is cut back.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "contact/contact_pair.hpp"

namespace cc::contact {

ContactPair::Augmentation ContactPair::augment() {
  if (!config_.augmented) return Augmentation::Converged;
  double largestTraction = 0, largestUpdate = 0;
  for (const PairPoint& point : points_) {
    const PointTrial& t = point.trial;
    const bool active = t.valid && t.state != ContactState::Open;
    const double normal = active ? t.normalTraction : 0.0;
    largestTraction = std::max(largestTraction, std::abs(normal));
    largestUpdate = std::max(largestUpdate, std::abs(normal - point.multiplierNormal));
    if (t.valid && t.state == ContactState::Stick)
      largestUpdate = std::max(largestUpdate, (t.traction - t.tractionBase).norm());
  }
  if (largestUpdate <= config_.augmentationTolerance * largestTraction) {
    return Augmentation::Converged;
  }
  if (augmentations_ >= config_.maxAugmentations) {
    lastAugmentationMessage_ = fmt::format(
        "contact pair '{}': {} augmentations did not reach aug_tol (multiplier update {:.3g} "
        "of max |N| = {:.3g}); raise eps_n/eps_t or aug_max",
        config_.name, augmentations_, largestUpdate, largestTraction);
    return Augmentation::Failed;
  }
  for (PairPoint& point : points_) {
    const PointTrial& t = point.trial;
    const bool active = t.valid && t.state != ContactState::Open;
    point.multiplierNormal = active ? t.normalTraction : 0.0;
    if (t.valid && t.state == ContactState::Stick)
      point.tractionAugmentation += t.traction - t.tractionBase;
  }
  ++augmentations_;
  return Augmentation::Updated;
}

void ContactPair::commitAugmentation() {
  for (PairPoint& point : points_) {
    point.committedMultiplierNormal = point.multiplierNormal;
    point.tractionAugmentation.setZero();  // T^(n+1) includes it
  }
  augmentations_ = 0;
}

void ContactPair::restoreAugmentation() {
  for (PairPoint& point : points_) {
    point.multiplierNormal = point.committedMultiplierNormal;
    point.tractionAugmentation.setZero();
  }
  augmentations_ = 0;
}

}  // namespace cc::contact
