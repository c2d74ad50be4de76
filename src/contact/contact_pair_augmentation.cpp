// Augmented Lagrangian enforcement of a contact pair (issue 16, part 3a): Uzawa updates per load
// step. Within a Newton solve the multipliers are constants, so the paper's residual/tangent
// split and the exact tangent are unchanged; only N = min(0, lambda_N + eps_N g) and the
// traction the trial step starts from, Lambda_T = T^(n) carried to the current point plus A . rho_i
// (eq. (51) applied to the augmentation A), carry them. After a converged solve the Uzawa image
//   lambda_N <- N,  A <- A + (T - Lambda_T), i.e. Lambda_T <- T, at every point in contact
// (Laursen & Simo's lambda_T <- P(lambda_T + eps_T g_T), the return-mapped traction, sliding
// points included) is combined with the last aug_depth images by Anderson acceleration
// (anderson_acceleration.hpp: plain Uzawa contracts like k / (k + eps) per update, hundreds of
// updates at a soft penalty), until the sum over points of w |N - lambda_N| plus, over sticking
// points, w |T - Lambda_T|, each weighted by max(1, eps_ref / eps), is at most aug_tol times the
// normal contact force sum w |N|. For a point in contact |N - lambda_N| = eps_N |g| and for a
// sticking one |T - Lambda_T| = eps_T |Delta rho_t|: the rule bounds the mean penetration and slip
// under stick by aug_tol (mean |N|) / max(eps, eps_ref), eps_ref the automatic penalty. A sliding
// point needs no tangential multiplier: its traction is mu |N| (the cone acts on the augmented N)
// in the direction of the trial, so Lambda_T only steers that direction; its update is not in the
// rule. Measured limits: docs/verification/augmented_lagrangian.md.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "contact/contact_pair.hpp"

namespace cc::contact {

ContactPair::Augmentation ContactPair::augment() {
  if (!config_.augmented) return Augmentation::Converged;
  const auto [force, update] = measureAugmentation();
  if (update <= config_.augmentationTolerance * force) return Augmentation::Converged;
  if (augmentations_ >= config_.maxAugmentations) {
    lastAugmentationMessage_ = fmt::format(
        "contact pair '{}': {} augmentations did not reach aug_tol (multiplier update {:.3g} "
        "of the normal contact force {:.3g}); raise eps_n/eps_t or aug_max",
        config_.name, augmentations_, update, force);
    return Augmentation::Failed;
  }
  if (force > 0 && raisePenaltyIfStalled(update / force)) {
    ++augmentations_;
    return Augmentation::Updated;  // solved again with the same multipliers, stiffer penalty
  }
  updateMultipliers();
  ++augmentations_;
  return Augmentation::Updated;
}

// Integrated over the surface (weights w): the update of the contact force against the contact
// force. A rule on the largest point update stalled at the corners of a pressed block, where the
// pressure is singular and its multiplier converges slowest. An update is eps |g| (eps |Delta
// rho_t| under stick); weighting it by eps_ref / eps where eps is below the automatic penalty
// eps_ref bounds the penetration left by aug_tol |N| / max(eps, eps_ref): the same bound for
// every softer penalty, so that the results do not depend on it.
ContactPair::AugmentationMeasure ContactPair::measureAugmentation() const {
  const double normalWeight = std::max(1.0, config_.referencePenalty / config_.law.penaltyNormal);
  const double tangentialWeight =
      config_.law.penaltyTangential > 0
          ? std::max(1.0, config_.referencePenalty / config_.law.penaltyTangential)
          : 1.0;
  AugmentationMeasure measure;
  for (const PairPoint& point : points_) {
    const PointTrial& t = point.trial;
    if (!t.valid) continue;
    const bool active = t.state != ContactState::Open;
    const double normal = active ? t.normalTraction : 0.0;
    measure.force += t.weight * std::abs(normal);
    measure.update += normalWeight * t.weight * std::abs(normal - point.multiplierNormal);
    if (t.state == ContactState::Stick)
      measure.update += tangentialWeight * t.weight * (t.traction - t.tractionBase).norm();
  }
  return measure;
}

// The Uzawa image of the multipliers (4 per point: lambda_N and the augmentation A), then
// Anderson's combination of the last images (aug_depth; 0 keeps plain Uzawa). Lambda_T <- T at
// sliding points as well: a point that kept the augmentation of its last sticking update started
// its next trial far inside or outside the cone, and the points where the block turns from stick
// to slip flipped at every update; which of them flipped was decided by round-off (the soft block
// of tests/regression/contact/check_augmented_kernels.py: 5 steps or 32 steps with 3 cut-backs by
// the BLAS kernels). With the slip traction as Lambda_T a point that sticks again starts on the
// cone.
void ContactPair::updateMultipliers() {
  const std::size_t count = points_.size();
  Eigen::VectorXd current(4 * count), image(4 * count), weights(4 * count);
  for (std::size_t k = 0; k < count; ++k) {
    const PairPoint& point = points_[k];
    const PointTrial& t = point.trial;
    const bool active = t.valid && t.state != ContactState::Open;
    Eigen::Vector3d augmentation = point.tractionAugmentation;
    current.segment<4>(4 * k) << point.multiplierNormal, augmentation;
    if (active) augmentation += t.traction - t.tractionBase;
    image.segment<4>(4 * k) << (active ? t.normalTraction : 0.0), augmentation;
    weights.segment<4>(4 * k).setConstant(t.valid ? t.weight : 0.0);
  }
  const Eigen::VectorXd next = accelerator_.next(current, image, weights);
  for (std::size_t k = 0; k < count; ++k) {
    PairPoint& point = points_[k];
    // A point without a projection has weight 0 in the combination: it takes its plain image
    // (no multiplier), as in plain Uzawa, not whatever the combination leaves there.
    const Eigen::VectorXd& source = point.trial.valid ? next : image;
    // A compressive multiplier only (N = min(0, lambda_N + eps_N g)): a combination may
    // overshoot to tension where the plain image would be 0.
    point.multiplierNormal = std::min(0.0, source[4 * k]);
    point.tractionAugmentation = source.segment<3>(4 * k + 1);
  }
}

// A stall of the updates (aug_grow): plain Uzawa contracts like k / (k + eps) per update for a
// contact mode of stiffness k, and Anderson's combination restarts where points change state;
// at eps = 1e-2 eps_ref example 6.1(b) hovered at 1.6e-3 of the normal force (aug_tol 1e-3) for
// 100 updates where the block's leading edge turns from stick to slip, and the run failed at any
// step size. The converged multipliers do not depend on eps (they satisfy the constraint), so a
// pair whose updates have not halved over kStallWindow updates, at a penalty below the
// automatic one, takes a tenfold penalty (at most the automatic one) and keeps it for the rest
// of the run; the Anderson history restarts because the map changed.
namespace {
constexpr std::size_t kStallWindow = 10;
constexpr double kStallProgress = 0.5;
constexpr double kPenaltyGrowth = 10;
}  // namespace

bool ContactPair::raisePenaltyIfStalled(double ratio) {
  updateRatios_.push_back(ratio);
  const std::size_t count = updateRatios_.size();
  if (!config_.growPenalty || count <= kStallWindow ||
      ratio <= kStallProgress * updateRatios_[count - 1 - kStallWindow]) {
    return false;
  }
  const double reference = config_.referencePenalty;
  // Each penalty below the automatic one grows by up to kPenaltyGrowth, none beyond it (a
  // frictionless pair's eps_T = 0 stays 0).
  auto raised = [reference](double penalty) {
    return penalty > 0 && penalty < reference ? std::min(kPenaltyGrowth * penalty, reference)
                                              : penalty;
  };
  const double beforeNormal = builtPenaltyNormal_, beforeTangential = builtPenaltyTangential_;
  builtPenaltyNormal_ = raised(beforeNormal);
  builtPenaltyTangential_ = raised(beforeTangential);
  if (builtPenaltyNormal_ == beforeNormal && builtPenaltyTangential_ == beforeTangential) {
    return false;
  }
  // augment() runs after the solves of a step, when no continuation scales the penalties.
  config_.law.penaltyNormal = builtPenaltyNormal_;
  config_.law.penaltyTangential = builtPenaltyTangential_;
  accelerator_.reset();
  updateRatios_.clear();
  augmentationNote_ = fmt::format(
      "contact pair '{}': the multiplier updates stalled at {:.3g} of the normal contact force "
      "(aug_tol {:.3g}) after {} updates; eps_n {:.4g} -> {:.4g}, eps_t {:.4g} -> {:.4g} (at most "
      "the automatic {:.4g}) for the rest of the run (aug_grow=no keeps them)",
      config_.name, ratio, config_.augmentationTolerance, augmentations_ + 1, beforeNormal,
      builtPenaltyNormal_, beforeTangential, builtPenaltyTangential_, reference);
  return true;
}

void ContactPair::commitAugmentation() {
  for (PairPoint& point : points_) {
    point.committedMultiplierNormal = point.multiplierNormal;
    point.tractionAugmentation.setZero();  // T^(n+1) includes it
  }
  augmentations_ = 0;
  updateRatios_.clear();
  accelerator_.reset();
}

void ContactPair::restoreAugmentation() {
  for (PairPoint& point : points_) {
    point.multiplierNormal = point.committedMultiplierNormal;
    point.tractionAugmentation.setZero();
  }
  augmentations_ = 0;
  updateRatios_.clear();
  accelerator_.reset();
}

}  // namespace cc::contact
