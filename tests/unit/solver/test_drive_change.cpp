// When a drive turns (solver/drive_change.hpp): the corners of a load path turn, smooth paths
// sampled at the steps of the decks continue, and the test scales the last step to the new
// step's size.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "solver/drive_change.hpp"

namespace cc {
namespace {

using Path = std::function<Eigen::Vector3d(double)>;

bool continuesAt(const Path& path, double before, double now, double next) {
  return driveContinues(path(before), path(now), path(next), (next - now) / (now - before));
}

TEST(DriveChange, ThePressToDragCornerOfTheIroningDecksTurns) {
  // ux = 4 max(t - 0.2, 0) / 0.8, uz = -1.4 min(t / 0.2, 1), dt = 0.01: the last press step
  // moves (0, 0, -0.07), the first drag step (0.05, 0, 0): a change of 0.086, 1.2 times the
  // larger.
  const Path ironing = [](double t) {
    return Eigen::Vector3d(4 * std::max(t - 0.2, 0.0) / 0.8, 0, -1.4 * std::min(t / 0.2, 1.0));
  };
  EXPECT_TRUE(continuesAt(ironing, 0.18, 0.19, 0.2));   // pressing
  EXPECT_FALSE(continuesAt(ironing, 0.19, 0.2, 0.21));  // the corner
  EXPECT_TRUE(continuesAt(ironing, 0.2, 0.21, 0.22));   // dragging
}

TEST(DriveChange, ACircleInEightyStepsContinues) {
  // Each step turns the motion by 2 pi / 80: a change of 0.079 of its length.
  const double step = 2 * std::numbers::pi / 80;
  const Path circle = [](double angle) {
    return Eigen::Vector3d(3 * std::cos(angle), 3 * std::sin(angle), 0);
  };
  for (int k = 1; k < 80; ++k)
    EXPECT_TRUE(continuesAt(circle, (k - 1) * step, k * step, (k + 1) * step));
}

TEST(DriveChange, ASineInTwentyStepsTurnsOnlyNearItsPeaks) {
  // Sampled every 18 degrees: the change at the samples 0, 18, 36 and 54 degrees is 0, 0.10,
  // 0.21 and 0.36 of the larger increment, at 72 degrees (95 % of the amplitude) 0.66, and at
  // the peak, where the motion reverses, 2.
  const double step = 2 * std::numbers::pi / 20;
  const Path sine = [](double phase) { return Eigen::Vector3d(0, 0, std::sin(phase)); };
  for (int k = 0; k <= 3; ++k)
    EXPECT_TRUE(continuesAt(sine, (k - 1) * step, k * step, (k + 1) * step)) << k;
  EXPECT_FALSE(continuesAt(sine, 3 * step, 4 * step, 5 * step));
  EXPECT_FALSE(continuesAt(sine, 4 * step, 5 * step, 6 * step));
}

TEST(DriveChange, AReversalAStartAndAStopTurnARestContinues) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3);
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(3);
  EXPECT_FALSE(driveContinues(zero, one, zero, 1.0));    // there and back
  EXPECT_FALSE(driveContinues(zero, zero, one, 1.0));    // starts at the step
  EXPECT_FALSE(driveContinues(zero, one, one, 1.0));     // stops at the step
  EXPECT_TRUE(driveContinues(one, one, one, 1.0));       // at rest
  EXPECT_TRUE(driveContinues(zero, one, 2 * one, 1.0));  // constant velocity
}

TEST(DriveChange, TheLastStepIsScaledToTheNewStepsSize) {
  // Constant velocity 1 with a step of 1 followed by a cut-back step of 0.25: continues when
  // the last increment is scaled by 0.25, and would turn if it were compared unscaled.
  const Eigen::VectorXd before = Eigen::VectorXd::Zero(1);
  const Eigen::VectorXd now = Eigen::VectorXd::Ones(1);
  const Eigen::VectorXd next = Eigen::VectorXd::Constant(1, 1.25);
  EXPECT_TRUE(driveContinues(before, now, next, 0.25));
  EXPECT_FALSE(driveContinues(before, now, next, 1.0));
}

}  // namespace
}  // namespace cc
