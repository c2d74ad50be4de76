// Whether the drive of a step continues the last step's: the condition under which
// `predictor=extrapolate` extrapolates past a rigid surface's motion (load_stepper.cpp says why
// only that drive). A constant-velocity prediction carries on the last step's motion; where the
// drive turns (a press followed by a drag), it carries the old motion into the new one. On the
// ironing die as a rigid cylinder (STAS, mu = 0.3) the slab extrapolated downwards under a die
// that moves sideways changed the state of 200 of the 256 contact points at the first drag
// step's first iterate, and the step took 17 Newton iterations, against 6 from the converged
// state (docs/verification/sliding.md, forty-fourth session). Kept apart from the stepper so
// that unit tests can feed it drives.
#pragma once

#include <Eigen/Core>
#include <algorithm>

namespace cc {

// A drive "turns" when its increment over the new step differs from the last step's, scaled to
// the new step's size, by more than this share of the larger of the two. A smooth drive
// changes by O(dt) per step: a circle in 80 steps by 0.08, a sine in 20 steps per period by
// 0.36 at most up to 81 % of its amplitude (0.66 at 95 %). A corner in the path changes by
// O(1): press -> drag 1.2, a reversal 2, a drive that starts or stops at the step 1.
inline constexpr double kDriveTurn = 0.5;

// One channel of the drive (values of the same unit) at the three step ends t_(n-1), t_n and
// t_(n+1); `stepRatio` = (t_(n+1) - t_n) / (t_n - t_(n-1)). True when the channel does not turn
// (a channel that does not move in either step continues).
inline bool driveContinues(const Eigen::VectorXd& before, const Eigen::VectorXd& now,
                           const Eigen::VectorXd& next, double stepRatio) {
  const Eigen::VectorXd last = (now - before) * stepRatio;
  const Eigen::VectorXd coming = next - now;
  const double scale = std::max(last.norm(), coming.norm());
  return (coming - last).norm() <= kDriveTurn * scale;
}

}  // namespace cc
