// Gauss-Legendre rules: exactness for monomials up to degree 2n-1 (and not beyond), published
// nodes/weights of the low-order rules, and the tensor-product quad and hex rules.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "fem/quadrature.hpp"

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Summing at most 6^3 terms of size <= 8 accumulates a few ulps of the result.
constexpr double kRoundOff = 64 * kEps;

double exactMonomialIntegral(int degree) {  // int_{-1}^{1} x^degree dx
  return degree % 2 == 1 ? 0.0 : 2.0 / (degree + 1);
}

double integrate1D(const cc::GaussRule1D& rule, int degree) {
  double sum = 0;
  for (std::size_t i = 0; i < rule.points.size(); ++i) {
    sum += rule.weights[i] * std::pow(rule.points[i], degree);
  }
  return sum;
}

TEST(GaussLegendre, IntegratesMonomialsUpToDegree2nMinus1Exactly) {
  for (int n = 1; n <= cc::kMaxGaussPoints; ++n) {
    const cc::GaussRule1D rule = cc::gaussLegendre(n);
    ASSERT_EQ(rule.points.size(), static_cast<std::size_t>(n));
    for (int degree = 0; degree <= 2 * n - 1; ++degree) {
      EXPECT_NEAR(integrate1D(rule, degree), exactMonomialIntegral(degree), kRoundOff)
          << n << " points, degree " << degree;
    }
    // Degree 2n is not exact: the remainder for x^2n is the classical
    // 2^(2n+1) (n!)^4 / ((2n+1) ((2n)!)^2) (Abramowitz & Stegun 25.4.30 with f^(2n) = (2n)!).
    const double remainder = std::pow(2.0, 2 * n + 1) * std::pow(std::tgamma(n + 1), 4) /
                             ((2 * n + 1) * std::pow(std::tgamma(2 * n + 1), 2));
    EXPECT_NEAR(exactMonomialIntegral(2 * n) - integrate1D(rule, 2 * n), remainder, kRoundOff)
        << n << " points";
  }
}

TEST(GaussLegendre, MatchesPublishedLowOrderRules) {
  const cc::GaussRule1D one = cc::gaussLegendre(1);
  EXPECT_EQ(one.points[0], 0.0);
  EXPECT_NEAR(one.weights[0], 2.0, kEps);
  const cc::GaussRule1D two = cc::gaussLegendre(2);
  EXPECT_NEAR(two.points[1], 1.0 / std::sqrt(3.0), kEps);
  EXPECT_NEAR(two.points[0], -1.0 / std::sqrt(3.0), kEps);
  EXPECT_NEAR(two.weights[0], 1.0, 2 * kEps);
  const cc::GaussRule1D three = cc::gaussLegendre(3);
  EXPECT_NEAR(three.points[2], std::sqrt(0.6), kEps);
  EXPECT_EQ(three.points[1], 0.0);
  EXPECT_NEAR(three.weights[1], 8.0 / 9.0, 2 * kEps);
  EXPECT_NEAR(three.weights[2], 5.0 / 9.0, 2 * kEps);
  // Abramowitz & Stegun, Table 25.4, n = 6.
  const cc::GaussRule1D six = cc::gaussLegendre(6);
  EXPECT_NEAR(six.points[5], 0.932469514203152, 1e-15);
  EXPECT_NEAR(six.weights[5], 0.171324492379170, 1e-15);
  EXPECT_NEAR(six.points[3], 0.238619186083197, 1e-15);
  EXPECT_NEAR(six.weights[3], 0.467913934572691, 1e-15);
}

TEST(GaussLegendre, PointsAreAscendingAndSymmetric) {
  for (int n = 1; n <= cc::kMaxGaussPoints; ++n) {
    const cc::GaussRule1D rule = cc::gaussLegendre(n);
    for (int i = 0; i < n; ++i) {
      EXPECT_EQ(rule.points[i], -rule.points[n - 1 - i]);
      EXPECT_EQ(rule.weights[i], rule.weights[n - 1 - i]);
      if (i > 0) {
        EXPECT_LT(rule.points[i - 1], rule.points[i]);
      }
    }
  }
}

TEST(GaussLegendre, RejectsUnsupportedPointCounts) {
  EXPECT_THROW(cc::gaussLegendre(0), std::invalid_argument);
  EXPECT_THROW(cc::gaussLegendre(cc::kMaxGaussPoints + 1), std::invalid_argument);
}

TEST(TensorRules, QuadIntegratesMonomialsExactly) {
  for (int n = 1; n <= cc::kMaxGaussPoints; ++n) {
    const auto rule = cc::gaussQuad(n);
    ASSERT_EQ(rule.size(), static_cast<std::size_t>(n * n));
    for (int a = 0; a <= 2 * n - 1; ++a) {
      for (int b = 0; b <= 2 * n - 1; ++b) {
        double sum = 0;
        for (const auto& point : rule) {
          sum += point.weight * std::pow(point.xi[0], a) * std::pow(point.xi[1], b);
        }
        EXPECT_NEAR(sum, exactMonomialIntegral(a) * exactMonomialIntegral(b), kRoundOff)
            << n << " points, x^" << a << " y^" << b;
      }
    }
  }
}

TEST(TensorRules, HexIntegratesMonomialsExactlyAndFixedVariantAgrees) {
  for (int n = 1; n <= cc::kMaxGaussPoints; ++n) {
    const auto rule = cc::gaussHex(n);
    ASSERT_EQ(rule.size(), static_cast<std::size_t>(n * n * n));
    for (int a = 0; a <= 2 * n - 1; ++a) {
      for (int b = 0; b <= 2 * n - 1; ++b) {
        for (int c = 0; c <= 2 * n - 1; ++c) {
          double sum = 0;
          for (const auto& p : rule) {
            sum += p.weight * std::pow(p.xi[0], a) * std::pow(p.xi[1], b) * std::pow(p.xi[2], c);
          }
          const double exact =
              exactMonomialIntegral(a) * exactMonomialIntegral(b) * exactMonomialIntegral(c);
          EXPECT_NEAR(sum, exact, kRoundOff) << n << " points, x^" << a << " y^" << b << " z^" << c;
        }
      }
    }
  }
  const auto dynamicRule = cc::gaussHex(2);
  const auto fixedRule = cc::gaussHexFixed<2>();
  for (std::size_t g = 0; g < fixedRule.size(); ++g) {
    EXPECT_EQ(fixedRule[g].xi, dynamicRule[g].xi);
    EXPECT_EQ(fixedRule[g].weight, dynamicRule[g].weight);
  }
}

}  // namespace
