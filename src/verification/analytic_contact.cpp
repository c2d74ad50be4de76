// Closed-form Hertz and Cattaneo-Mindlin solutions, and the half-space axis displacements (by
// quadrature of Boussinesq's and Cerruti's point-load solutions over the contact tractions).
#include "verification/analytic_contact.hpp"

#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>

#include "fem/quadrature.hpp"

namespace cc::verification {

namespace {

constexpr double kPi = std::numbers::pi;
// Composite Gauss rule over [0, pi/2]: the Boussinesq kernel changes on the scale of the depth,
// so many panels keep the axis displacement accurate to ~1e-10 down to depth ~ a / 100.
constexpr int kQuadraturePanels = 200;
constexpr int kPointsPerPanel = 6;
// Bisection on log(load) to this relative width (well below any discretization error we measure).
constexpr double kLoadTolerance = 1e-12;
constexpr int kMaxBracketDoublings = 200;

double shearModulus(double youngs, double poisson) {
  return youngs / (2 * (1 + poisson));
}

// Integral over [0, radius] of sqrt(1 - s^2/radius^2) kernel(s) ds, with s = radius sin(theta) so
// that the square-root edge becomes smooth: integral of cos^2(theta) kernel(radius sin theta).
double integrateElliptic(double radius, const std::function<double(double)>& kernel) {
  static const GaussRule1D rule = gaussLegendre(kPointsPerPanel);
  const double panel = 0.5 * kPi / kQuadraturePanels;
  double sum = 0;
  for (int k = 0; k < kQuadraturePanels; ++k) {
    for (int q = 0; q < kPointsPerPanel; ++q) {
      const double theta = panel * (k + 0.5 * (1 + rule.points[q]));
      const double cosine = std::cos(theta);
      sum += 0.5 * panel * rule.weights[q] * cosine * cosine * kernel(radius * std::sin(theta));
    }
  }
  return radius * sum;
}

// Vertical displacement at depth z on the axis per unit pressure on the ring of radius s (width
// ds): Boussinesq's point load 1/(4 pi G) (z^2/rho^3 + 2 (1 - nu)/rho) times 2 pi s.
double boussinesqAxisKernel(double s, double depth, double shear, double poisson) {
  const double rho = std::hypot(s, depth);
  if (rho == 0) return (1 - poisson) / shear;  // the s -> 0 limit at the surface
  return s / (2 * shear) * (depth * depth / (rho * rho * rho) + 2 * (1 - poisson) / rho);
}

// Displacement along the load at depth z on the axis per unit tangential traction on a ring:
// Cerruti's point load averaged over the ring angle (<x^2> = s^2 / 2) times 2 pi s.
double cerrutiAxisKernel(double s, double depth, double shear, double poisson) {
  const double rho = std::hypot(s, depth);
  if (rho == 0) return (2 - poisson) / (2 * shear);
  const double halfSquare = 0.5 * s * s;
  return s / (2 * shear) *
         (1 / rho + halfSquare / (rho * rho * rho) +
          (1 - 2 * poisson) *
              (1 / (rho + depth) - halfSquare / (rho * (rho + depth) * (rho + depth))));
}

// Finds x > 0 with f(x) = target for f increasing from f(lower) <= target, by doubling an upper
// bound and bisecting on log(x).
double solveIncreasing(const std::function<double(double)>& f, double target, double lower) {
  double upper = 2 * lower;
  for (int k = 0; f(upper) < target; ++k) {
    if (k == kMaxBracketDoublings) throw std::domain_error("no load reaches this approach");
    lower = upper;
    upper *= 2;
  }
  while (upper - lower > kLoadTolerance * upper) {
    const double middle = std::sqrt(lower * upper);
    (f(middle) < target ? lower : upper) = middle;
  }
  return 0.5 * (lower + upper);
}

}  // namespace

double ElasticPair::contactModulus() const {
  return 1 / ((1 - poisson1 * poisson1) / youngs1 + (1 - poisson2 * poisson2) / youngs2);
}

double ElasticPair::tangentialComplianceFactor() const {
  return (2 - poisson1) / shearModulus(youngs1, poisson1) +
         (2 - poisson2) / shearModulus(youngs2, poisson2);
}

double ElasticPair::dundursBeta() const {
  const double shear1 = shearModulus(youngs1, poisson1), shear2 = shearModulus(youngs2, poisson2);
  return ((1 - 2 * poisson1) / shear1 - (1 - 2 * poisson2) / shear2) /
         (2 * ((1 - poisson1) / shear1 + (1 - poisson2) / shear2));
}

double HertzSphere::contactRadius(double load) const {
  return std::cbrt(3 * load * radius / (4 * bodies.contactModulus()));
}

double HertzSphere::peakPressure(double load) const {
  const double a = contactRadius(load);
  return 3 * load / (2 * kPi * a * a);
}

double HertzSphere::approach(double load) const {
  const double a = contactRadius(load);
  return a * a / radius;
}

double HertzSphere::loadAtApproach(double delta) const {
  return 4.0 / 3.0 * bodies.contactModulus() * std::sqrt(radius) * std::pow(delta, 1.5);
}

double HertzSphere::axisDisplacement(int body, double depth, double load) const {
  const double youngs = body == 1 ? bodies.youngs1 : bodies.youngs2;
  const double poisson = body == 1 ? bodies.poisson1 : bodies.poisson2;
  if (std::isinf(youngs)) return 0;
  const double shear = shearModulus(youngs, poisson);
  return peakPressure(load) * integrateElliptic(contactRadius(load), [&](double s) {
           return boussinesqAxisKernel(s, depth, shear, poisson);
         });
}

double HertzSphere::probeApproach(double load, double depth1, double depth2) const {
  return approach(load) - axisDisplacement(1, depth1, load) - axisDisplacement(2, depth2, load);
}

double HertzSphere::loadAtProbeApproach(double delta, double depth1, double depth2) const {
  if (delta <= 0) return 0;
  // The probes approach less than distant points, so Hertz' load at `delta` is a lower bound.
  return solveIncreasing([&](double load) { return probeApproach(load, depth1, depth2); }, delta,
                         loadAtApproach(delta));
}

double HertzCylinder::halfWidth(double loadPerLength) const {
  return std::sqrt(4 * loadPerLength * radius / (kPi * bodies.contactModulus()));
}

double HertzCylinder::peakPressure(double loadPerLength) const {
  return 2 * loadPerLength / (kPi * halfWidth(loadPerLength));
}

double CattaneoMindlinSphere::stickRadius(double load, double tangentialLoad) const {
  return hertz.contactRadius(load) * std::cbrt(1 - tangentialLoad / (friction * load));
}

double CattaneoMindlinSphere::tangentialApproach(double load, double tangentialLoad) const {
  const double a = hertz.contactRadius(load);
  return 3 * friction * load / (16 * a) * hertz.bodies.tangentialComplianceFactor() *
         (1 - std::pow(1 - tangentialLoad / (friction * load), 2.0 / 3.0));
}

double CattaneoMindlinSphere::axisTangentialDisplacement(int body, double depth, double load,
                                                         double tangentialLoad) const {
  const double youngs = body == 1 ? hertz.bodies.youngs1 : hertz.bodies.youngs2;
  const double poisson = body == 1 ? hertz.bodies.poisson1 : hertz.bodies.poisson2;
  if (std::isinf(youngs)) return 0;
  const double shear = shearModulus(youngs, poisson);
  auto kernel = [&](double s) { return cerrutiAxisKernel(s, depth, shear, poisson); };
  // Traction mu p0 sqrt(1 - r^2/a^2) minus the stick-zone correction mu p0 (c/a) sqrt(1 - r^2/c^2).
  const double a = hertz.contactRadius(load);
  const double c = stickRadius(load, tangentialLoad);
  const double scale = friction * hertz.peakPressure(load);
  return scale * (integrateElliptic(a, kernel) - c / a * integrateElliptic(c, kernel));
}

double CattaneoMindlinSphere::probeTangentialApproach(double load, double tangentialLoad,
                                                      double depth1, double depth2) const {
  return tangentialApproach(load, tangentialLoad) -
         axisTangentialDisplacement(1, depth1, load, tangentialLoad) -
         axisTangentialDisplacement(2, depth2, load, tangentialLoad);
}

double CattaneoMindlinSphere::tangentialLoadAtProbeApproach(double load, double approach,
                                                            double depth1, double depth2) const {
  if (approach <= 0) return 0;
  const double limit = friction * load;
  if (probeTangentialApproach(load, limit, depth1, depth2) <= approach) return limit;
  double lower = 0, upper = limit;
  while (upper - lower > kLoadTolerance * limit) {
    const double middle = 0.5 * (lower + upper);
    (probeTangentialApproach(load, middle, depth1, depth2) < approach ? lower : upper) = middle;
  }
  return 0.5 * (lower + upper);
}

double CattaneoMindlinCylinder::stickHalfWidth(double loadPerLength,
                                               double tangentialLoadPerLength) const {
  return hertz.halfWidth(loadPerLength) *
         std::sqrt(1 - tangentialLoadPerLength / (friction * loadPerLength));
}

}  // namespace cc::verification
