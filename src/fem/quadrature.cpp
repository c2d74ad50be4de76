// Gauss-Legendre nodes and weights (Newton iteration on the Legendre polynomial P_n) and the
// tensor-product rules built from them.
#include "fem/quadrature.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace cc {
namespace {

struct LegendreValue {
  double value;       // P_n(x)
  double derivative;  // P_n'(x)
};

// Bonnet's recurrence (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1}; derivative from
// (1 - x^2) P_n' = n (P_{n-1} - x P_n), valid in the open interval where the roots lie.
LegendreValue legendre(int n, double x) {
  double previous = 1.0;
  double current = x;
  for (int k = 1; k < n; ++k) {
    const double next = ((2 * k + 1) * x * current - k * previous) / (k + 1);
    previous = current;
    current = next;
  }
  return {current, n * (previous - x * current) / (1.0 - x * x)};
}

struct StoredRule {
  std::array<double, kMaxGaussPoints> points{};
  std::array<double, kMaxGaussPoints> weights{};
};

// Newton's method converges quadratically from the classical asymptotic guess
// cos(pi (i + 3/4) / (n + 1/2)); a fixed iteration cap guards against a non-terminating loop.
StoredRule computeRule(int n) {
  constexpr int kMaxNewtonIterations = 100;
  StoredRule rule;
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    for (int iteration = 0; iteration < kMaxNewtonIterations; ++iteration) {
      const LegendreValue p = legendre(n, x);
      const double step = p.value / p.derivative;
      x -= step;
      if (std::abs(step) <= std::numeric_limits<double>::epsilon()) break;
    }
    if (2 * i + 1 == n) x = 0.0;  // the middle root of an odd rule is exactly 0
    const double derivative = legendre(n, x).derivative;
    const double weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
    // Roots come out descending from +1; store the rule ascending and mirrored exactly.
    rule.points[n - 1 - i] = x;
    rule.points[i] = -x;
    rule.weights[i] = rule.weights[n - 1 - i] = weight;
  }
  return rule;
}

const std::array<StoredRule, kMaxGaussPoints>& allRules() {
  static const std::array<StoredRule, kMaxGaussPoints> rules = [] {
    std::array<StoredRule, kMaxGaussPoints> computed;
    for (int n = 1; n <= kMaxGaussPoints; ++n) computed[n - 1] = computeRule(n);
    return computed;
  }();
  return rules;
}

}  // namespace

GaussRule1D gaussLegendre(int numPoints) {
  if (numPoints < 1 || numPoints > kMaxGaussPoints) {
    throw std::invalid_argument("Gauss-Legendre rule needs 1 to " +
                                std::to_string(kMaxGaussPoints) + " points, got " +
                                std::to_string(numPoints));
  }
  const StoredRule& rule = allRules()[numPoints - 1];
  return {std::span<const double>(rule.points.data(), numPoints),
          std::span<const double>(rule.weights.data(), numPoints)};
}

std::vector<QuadraturePoint<2>> gaussQuad(int pointsPerDirection) {
  const GaussRule1D rule = gaussLegendre(pointsPerDirection);
  std::vector<QuadraturePoint<2>> points;
  points.reserve(pointsPerDirection * pointsPerDirection);
  for (int j = 0; j < pointsPerDirection; ++j) {
    for (int i = 0; i < pointsPerDirection; ++i) {
      points.push_back(
          {Eigen::Vector2d(rule.points[i], rule.points[j]), rule.weights[i] * rule.weights[j]});
    }
  }
  return points;
}

std::vector<QuadraturePoint<3>> gaussHex(int pointsPerDirection) {
  const GaussRule1D rule = gaussLegendre(pointsPerDirection);
  std::vector<QuadraturePoint<3>> points;
  points.reserve(pointsPerDirection * pointsPerDirection * pointsPerDirection);
  for (int k = 0; k < pointsPerDirection; ++k) {
    for (int j = 0; j < pointsPerDirection; ++j) {
      for (int i = 0; i < pointsPerDirection; ++i) {
        points.push_back({Eigen::Vector3d(rule.points[i], rule.points[j], rule.points[k]),
                          rule.weights[i] * rule.weights[j] * rule.weights[k]});
      }
    }
  }
  return points;
}

}  // namespace cc
