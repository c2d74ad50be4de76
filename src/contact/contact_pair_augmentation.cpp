// Augmented Lagrangian enforcement of a contact pair (issue 16, part 3a): Uzawa updates per load
// step. Within a Newton solve the multipliers are constants, so the paper's residual/tangent
// split and the exact tangent are unchanged; only N = min(0, lambda_N + eps_N g) and the
// traction the trial step starts from, Lambda_T = T^(n) carried to the current point plus A . rho_i
// (eq. (51) applied to the augmentation A), carry them. After a converged solve:
//   lambda_N <- N,  A <- A + (T - Lambda_T) at sticking points,
// until the sum over points of w |N - lambda_N| plus, over sticking points, w |T - Lambda_T| is
// at most aug_tol times the normal contact force sum w |N|. For a point in contact |N - lambda_N|
// = eps_N |g| and for a sticking point |T - Lambda_T| = eps_T |Delta rho_t|: the rule bounds
// the mean penetration and slip under stick by aug_tol (mean |N|) / eps. A sliding point needs no
// tangential multiplier: its traction is mu |N| (the cone acts on the augmented N) in the direction
// of the trial, so Lambda_T only steers that direction. Known limit
// (docs/verification/augmented_lagrangian.md): on 6.1(b) in sliding, Uzawa stalls at an update of
// about 1e-3 max|N| whatever the step size, so the step fails after aug_max updates and is cut
// back.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "contact/contact_pair.hpp"

namespace cc::contact {

ContactPair::Augmentation ContactPair::augment() {
  if (!config_.augmented) return Augmentation::Converged;
  // Integrated over the surface (weights w): the update of the contact force against the
  // contact force. A rule on the largest point update stalled at the corners of a pressed
  // block, where the pressure is singular and its multiplier converges slowest.
  double force = 0, update = 0;
  for (const PairPoint& point : points_) {
    const PointTrial& t = point.trial;
    if (!t.valid) continue;
    const bool active = t.state != ContactState::Open;
    const double normal = active ? t.normalTraction : 0.0;
    force += t.weight * std::abs(normal);
    update += t.weight * std::abs(normal - point.multiplierNormal);
    if (t.state == ContactState::Stick) update += t.weight * (t.traction - t.tractionBase).norm();
  }
  if (update <= config_.augmentationTolerance * force) return Augmentation::Converged;
  if (augmentations_ >= config_.maxAugmentations) {
    lastAugmentationMessage_ = fmt::format(
        "contact pair '{}': {} augmentations did not reach aug_tol (multiplier update {:.3g} "
        "of the normal contact force {:.3g}); raise eps_n/eps_t or aug_max",
        config_.name, augmentations_, update, force);
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
