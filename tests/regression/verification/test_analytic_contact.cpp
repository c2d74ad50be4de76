// The analytic references themselves (src/verification): Hertz and Cattaneo-Mindlin closed forms
// against independent identities (load = integral of the pressure, Mindlin's surface displacement,
// far-field point-load limits of Boussinesq and Cerruti), and the model-free contact measures on
// synthetic point clouds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "verification/analytic_contact.hpp"
#include "verification/contact_measures.hpp"

namespace cc::verification {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRigid = std::numeric_limits<double>::infinity();
// The composite Gauss quadrature of the axis displacements is accurate to ~1e-10 (relative).
constexpr double kQuadratureTolerance = 1e-9;

const ElasticPair kRigidOnSteel{kRigid, 0, 2.1e5, 0.3};
const ElasticPair kSimilar{1000, 0.3, 1000, 0.3};

double shear(double youngs, double poisson) {
  return youngs / (2 * (1 + poisson));
}

// Midpoint rule over [0, radius] in the variable s = radius sin(theta) (smooth integrand).
template <typename F>
double integrateRadially(double radius, F integrand) {
  const int n = 20000;
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    const double theta = 0.5 * kPi * (k + 0.5) / n;
    sum += integrand(radius * std::sin(theta)) * radius * std::cos(theta);
  }
  return sum * 0.5 * kPi / n;
}

TEST(HertzSphere, PressureIntegratesToTheLoadAndApproachIsInverse) {
  const HertzSphere hertz{10, kRigidOnSteel};
  const double load = 3.7e3;
  const double a = hertz.contactRadius(load), p0 = hertz.peakPressure(load);
  const double integral = integrateRadially(a, [&](double r) {
    return p0 * std::sqrt(std::max(0.0, 1 - r * r / (a * a))) * 2 * kPi * r;
  });
  EXPECT_NEAR(integral / load, 1, 1e-6);
  EXPECT_NEAR(hertz.loadAtApproach(hertz.approach(load)) / load, 1, 1e-12);
  // Surface deflection at the centre, closed form (1 - nu^2) pi p0 a / (2 E).
  EXPECT_NEAR(hertz.axisDisplacement(2, 0, load) / ((1 - 0.09) * kPi * p0 * a / (2 * 2.1e5)), 1,
              kQuadratureTolerance);
  EXPECT_EQ(hertz.axisDisplacement(1, 0, load), 0);  // rigid indenter
}

TEST(HertzSphere, AxisDisplacementTendsToBoussinesqPointLoadFarAway) {
  const HertzSphere hertz{10, kSimilar};
  const double load = 5, a = hertz.contactRadius(load);
  const double depth = 300 * a;
  // Boussinesq on the axis: P (3 - 2 nu) / (4 pi G z); the spread load differs by O((a/z)^2).
  const double pointLoad = load * (3 - 0.6) / (4 * kPi * shear(1000, 0.3) * depth);
  EXPECT_NEAR(hertz.axisDisplacement(2, depth, load) / pointLoad, 1, 1e-4);
}

TEST(HertzSphere, ProbeApproachSpansZeroToHertzAndInverts) {
  const HertzSphere hertz{100, kSimilar};
  const double load = 20;
  EXPECT_NEAR(hertz.probeApproach(load, 0, 0) / hertz.approach(load), 0, kQuadratureTolerance);
  EXPECT_NEAR(hertz.probeApproach(load, 1e7, 1e7) / hertz.approach(load), 1, 1e-6);
  const double approach = hertz.probeApproach(load, 16, 16);
  EXPECT_LT(approach, hertz.approach(load));
  EXPECT_NEAR(hertz.loadAtProbeApproach(approach, 16, 16) / load, 1, 1e-10);
}

TEST(HertzCylinder, PressureIntegratesToTheLoadPerLength) {
  const HertzCylinder hertz{50, kSimilar};
  const double load = 2.5, b = hertz.halfWidth(load), p0 = hertz.peakPressure(load);
  EXPECT_NEAR(kPi * b * p0 / 2 / load, 1, 1e-14);
  // b^2 = 4 P R / (pi E*), E* = E / (2 (1 - nu^2)) for two equal bodies.
  EXPECT_NEAR(b * b / (4 * load * 50 / (kPi * 1000 / (2 * (1 - 0.09)))), 1, 1e-14);
}

TEST(ElasticPair, DundursBetaVanishesForSimilarBodiesOnly) {
  EXPECT_EQ(kSimilar.dundursBeta(), 0);
  // Rigid on elastic: |beta| = (1 - 2 nu) / (2 (1 - nu)).
  EXPECT_NEAR(std::abs(kRigidOnSteel.dundursBeta()), 0.4 / 1.4, 1e-14);
}

TEST(CattaneoMindlinSphere, StickRadiusLimitsAndSurfaceDisplacement) {
  const CattaneoMindlinSphere cm{{100, kSimilar}, 0.3};
  const double load = 20, a = cm.hertz.contactRadius(load);
  EXPECT_DOUBLE_EQ(cm.stickRadius(load, 0), a);
  EXPECT_NEAR(cm.stickRadius(load, 0.3 * load), 0, 1e-12);
  for (double ratio : {0.2, 0.5, 0.9}) {
    const double q = ratio * 0.3 * load;
    // The stick zone moves rigidly: the surface centres of both bodies approach by exactly the
    // distant-point approach, so the probe approach at zero depth vanishes.
    EXPECT_NEAR(cm.probeTangentialApproach(load, q, 0, 0) / cm.tangentialApproach(load, q), 0,
                kQuadratureTolerance);
    EXPECT_NEAR(
        cm.tangentialLoadAtProbeApproach(load, cm.probeTangentialApproach(load, q, 8, 8), 8, 8) / q,
        1, 1e-10);
  }
  // Cerruti on the axis far below a tangential point load: Q (3 - 2 nu) / (8 pi G z).
  const double q = 0.5 * 0.3 * load, depth = 300 * a;
  const double pointLoad = q * (3 - 0.6) / (8 * kPi * shear(1000, 0.3) * depth);
  EXPECT_NEAR(cm.axisTangentialDisplacement(2, depth, load, q) / pointLoad, 1, 1e-4);
}

TEST(CattaneoMindlinCylinder, StickHalfWidthFollowsTheSquareRootLaw) {
  const CattaneoMindlinCylinder cm{{50, kSimilar}, 0.5};
  const double load = 2, b = cm.hertz.halfWidth(load);
  EXPECT_DOUBLE_EQ(cm.stickHalfWidth(load, 0), b);
  EXPECT_NEAR(cm.stickHalfWidth(load, 0.75 * 0.5 * load), 0.5 * b, 1e-14);
}

// A square grid of points of spacing `spacing` over [0, n spacing]^2 (a quarter model), in
// contact inside radius `contact` with pressure `pressure(r)`, sticking inside `stick`.
template <typename Pressure>
ContactPairRecord gridRecord(int n, double spacing, double contact, double stick,
                             Pressure pressure) {
  ContactPairRecord record;
  const int count = n * n;
  record.position.resize(3, count);
  record.gap.resize(count);
  record.normalTraction.resize(count);
  record.state.resize(count);
  record.weight.setConstant(count, spacing * spacing);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int k = i * n + j;
      const double x = (i + 0.5) * spacing, y = (j + 0.5) * spacing, r = std::hypot(x, y);
      record.position.col(k) << x, y, 0;
      const bool closed = r < contact;
      record.normalTraction[k] = closed ? -pressure(r) : 0;
      record.gap[k] = closed ? -1e-3 * pressure(r) : 1;
      record.state[k] = !closed ? 0 : (r < stick ? 1 : 2);
    }
  }
  return record;
}

TEST(ContactMeasures, EqualAreaRadiiAreWithinOneSpacing) {
  const double spacing = 0.05;
  const auto record = gridRecord(40, spacing, 1.0, 0.6, [](double r) { return 2 - r; });
  const ModelledPart quarter{0.25, 1};
  EXPECT_NEAR(equivalentRadius(contactArea(record), quarter), 1.0, spacing);
  EXPECT_NEAR(equivalentRadius(stickArea(record), quarter), 0.6, spacing);
  EXPECT_NEAR(peakPressure(record), 2 - std::sqrt(2) * 0.5 * spacing, 1e-14);
  EXPECT_NEAR(maxPenetration(record), 1e-3 * peakPressure(record), 1e-15);
}

// A point beside a free edge of the master (edge=fade's band) has its gap and pressure measured
// to the master's extension: the largest values must come from the points on the master.
TEST(ContactMeasures, PointsBesideTheMastersFreeEdgeDoNotSetThePeaks) {
  const double spacing = 0.05;
  auto record = gridRecord(40, spacing, 1.0, 0.6, [](double r) { return 2 - r; });
  const double peak = peakPressure(record), penetration = maxPenetration(record);
  record.edgeShare.setOnes(record.state.size());
  const int beside = 5 * 40 + 5;  // at x = y = 0.275: in contact (r < 1)
  ASSERT_NE(record.state[beside], 0);
  record.edgeShare[beside] = 0.3;
  record.normalTraction[beside] = -10 * peak;
  record.gap[beside] = -10 * penetration;
  EXPECT_EQ(peakPressure(record), peak);
  EXPECT_EQ(maxPenetration(record), penetration);
  // Nor is such a point the centre, however near the axis it lies: the next one on the master is.
  const ModelledPart quarter{0.25, 1};
  record.edgeShare[0] = 0.3;  // the point nearest to the axis, at (0.5, 0.5) spacing
  record.normalTraction[0] = -10 * peak;
  EXPECT_NEAR(centrePressure(record, quarter), 2 - std::hypot(0.5 * spacing, 1.5 * spacing), 1e-14);
  record.edgeShare[beside] = 1;  // on the master, the same point sets both
  EXPECT_EQ(peakPressure(record), 10 * peak);
  EXPECT_EQ(maxPenetration(record), 10 * penetration);
}

TEST(ContactMeasures, PressureDeviationIsZeroForUniformPressureOnly) {
  const auto uniform = gridRecord(10, 0.1, 10, 0, [](double) { return 3.0; });
  EXPECT_NEAR(pressureDeviation(uniform), 0, 1e-13);  // round-off of the 100-term mean
  auto bumped = uniform;
  bumped.normalTraction[7] *= 1.01;  // one point of 100 is 1% above: the mean rises by 0.01%
  EXPECT_NEAR(pressureDeviation(bumped), (1.01 - 1.0001) / 1.0001, 1e-12);
  // The same point beside a free edge of the master: neither the list nor the mean takes it.
  bumped.edgeShare.setOnes(bumped.state.size());
  bumped.edgeShare[7] = 0.5;
  EXPECT_NEAR(pressureDeviation(bumped), 0, 1e-13);
  // A strip of a plane-strain model: half-width from the area.
  EXPECT_NEAR(equivalentHalfWidth(contactArea(uniform), {0.5, 1.0}), 1.0, 1e-12);
}

}  // namespace
}  // namespace cc::verification
