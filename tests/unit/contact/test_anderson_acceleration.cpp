// Anderson acceleration (contact/anderson_acceleration.hpp) on affine fixed-point maps with a
// known fixed point: the slow contraction of a soft-penalty Uzawa iteration, eigenvalues of the
// iteration matrix k / (k + eps) close to 1.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "contact/anderson_acceleration.hpp"

namespace cc::contact {
namespace {

struct AffineMap {
  Eigen::MatrixXd matrix;  // G(x) = matrix x + shift
  Eigen::VectorXd shift;
  Eigen::VectorXd fixedPoint() const {
    const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(matrix.rows(), matrix.cols());
    return (identity - matrix).lu().solve(shift);
  }
  Eigen::VectorXd operator()(const Eigen::VectorXd& x) const { return matrix * x + shift; }
};

// A symmetric contraction with eigenvalues k / (k + eps) = 0.94 ... 0.999 for stiffnesses
// k = 16 ... 1000 and eps = 1 (a penalty 16 to 1000 times softer than the contact modes), in a
// rotated basis.
AffineMap softUzawaMap(int size) {
  Eigen::VectorXd eigenvalues(size);
  for (int i = 0; i < size; ++i) {
    const double k = 16.0 * std::pow(1000.0 / 16.0, double(i) / (size - 1));
    eigenvalues[i] = k / (k + 1.0);
  }
  const Eigen::MatrixXd random = Eigen::MatrixXd::Random(size, size);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(random);
  const Eigen::MatrixXd basis = qr.householderQ();
  return {basis * eigenvalues.asDiagonal() * basis.transpose(),
          Eigen::VectorXd::LinSpaced(size, -1, 1)};
}

// Iterations until |x - x*| <= 1e-8 |x*|, at most `limit`.
int iterationsToConverge(const AffineMap& map, int depth, int limit) {
  AndersonAcceleration anderson(depth);
  const Eigen::VectorXd solution = map.fixedPoint();
  const Eigen::VectorXd weights = Eigen::VectorXd::Ones(solution.size());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(solution.size());
  for (int k = 1; k <= limit; ++k) {
    x = anderson.next(x, map(x), weights);
    if ((x - solution).norm() <= 1e-8 * solution.norm()) return k;
  }
  return limit + 1;
}

// Plain iteration contracts the slowest mode by 1000/1001 per step: log(1e-8)/log(1000/1001)
// = 18 400 steps. With a depth at least the dimension, Anderson on an affine map is GMRES on
// (I - M) x = b and terminates after dimension + 1 steps (up to round-off).
TEST(AndersonAcceleration, SolvesASlowAffineContractionInDimensionPlusOneSteps) {
  const AffineMap map = softUzawaMap(6);
  const int plain = iterationsToConverge(map, 0, 30000);
  EXPECT_GE(plain, 15000);
  const int accelerated = iterationsToConverge(map, 6, 30000);
  EXPECT_LE(accelerated, 6 + 2) << accelerated;
}

// With a depth below the dimension it keeps a rolling window of differences: still far fewer
// updates than plain iteration (measured: 185 against 18 400 in 40 dimensions at depth 5).
TEST(AndersonAcceleration, ShallowDepthStillBeatsPlainIterationFiftyfold) {
  const AffineMap map = softUzawaMap(40);
  const int plain = iterationsToConverge(map, 0, 30000);
  const int accelerated = iterationsToConverge(map, 5, 30000);
  EXPECT_LE(50 * accelerated, plain) << accelerated << " against " << plain;
}

// Entries with weight 0 (points that are not valid) do not steer the combination, and a change
// in the number of unknowns (a new point set) starts again from the plain image.
TEST(AndersonAcceleration, RestartsOnANewSizeAndIgnoresZeroWeights) {
  AndersonAcceleration anderson(3);
  const Eigen::VectorXd weights = Eigen::VectorXd::Ones(2);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2);
  const Eigen::Vector2d image1(1, 1);
  EXPECT_EQ(anderson.next(x, image1, weights), image1);  // first call: the plain image
  const Eigen::Vector2d image2(1.5, 1.5);
  anderson.next(image1, image2, weights);
  EXPECT_EQ(anderson.historySize(), 1);
  const Eigen::Vector3d x3(0, 0, 0), image3(2, 2, 2);
  EXPECT_EQ(anderson.next(x3, image3, Eigen::VectorXd::Ones(3)), Eigen::VectorXd(image3));
  EXPECT_EQ(anderson.historySize(), 0);
  // Zero weight on the second entry: the map x -> 0.5 x + 1 on the first entry is solved after
  // one difference, whatever the second entry does.
  AndersonAcceleration weighted(2);
  const Eigen::Vector2d w(1, 0);
  Eigen::Vector2d y(0, 0);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d image(0.5 * y[0] + 1, std::pow(-3.0, k));
    y = weighted.next(y, image, w);
  }
  EXPECT_NEAR(y[0], 2.0, 1e-12);
}

}  // namespace
}  // namespace cc::contact
