// Closed-form contact solutions for verification (K. L. Johnson, Contact Mechanics, 1985, ch. 3,
// 4 and 7):
// Hertz sphere and cylinder, Cattaneo-Mindlin partial slip, and the half-space displacements on
// the contact axis that turn "approach of distant points" into the approach of probe points.
#pragma once

namespace cc::verification {

// Two elastic bodies; a rigid body has youngs = infinity (its compliance term vanishes).
struct ElasticPair {
  double youngs1, poisson1;  // body 1 (the indenter, above the contact plane)
  double youngs2, poisson2;  // body 2 (below)

  // 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (Johnson §4.2).
  double contactModulus() const;
  // (2 - nu1)/G1 + (2 - nu2)/G2: the tangential compliance factor of Mindlin (Johnson §7.2).
  double tangentialComplianceFactor() const;
  // Dundurs' second parameter beta (Johnson §5.2); Cattaneo-Mindlin needs beta = 0.
  double dundursBeta() const;
};

// Hertz, sphere of radius R on a flat (or two spheres with 1/R = 1/R1 + 1/R2), total load P.
struct HertzSphere {
  double radius;
  ElasticPair bodies;

  double contactRadius(double load) const;    // a = (3 P R / 4 E*)^(1/3)
  double peakPressure(double load) const;     // p0 = 3 P / (2 pi a^2)
  double approach(double load) const;         // delta = a^2 / R
  double loadAtApproach(double delta) const;  // P = 4/3 E* sqrt(R) delta^(3/2)
  // Displacement of the axis point at `depth` in body `body` (1 or 2) towards the far field of
  // that body, relative to infinity: Boussinesq's point load integrated over the Hertz pressure.
  // (Johnson §3.2); depth = 0 gives the surface deflection (1 - nu^2) pi p0 a / (2 E) (§3.4).
  double axisDisplacement(int body, double depth, double load) const;
  // Approach of the axis points at depth1 in body 1 and depth2 in body 2:
  // delta - u1(depth1) - u2(depth2); infinite depths give Hertz' delta.
  double probeApproach(double load, double depth1, double depth2) const;
  // The load P whose probeApproach equals `approach` (monotone; solved by bisection).
  double loadAtProbeApproach(double approach, double depth1, double depth2) const;
};

// Hertz, two cylinders with parallel axes (plane strain), load P per unit length.
struct HertzCylinder {
  double radius;
  ElasticPair bodies;

  double halfWidth(double loadPerLength) const;     // b = sqrt(4 P R / (pi E*))
  double peakPressure(double loadPerLength) const;  // p0 = 2 P / (pi b)
};

// Cattaneo-Mindlin: the Hertz contact under normal load P, then a tangential load Q < mu P
// (elastically similar bodies, beta = 0, so the normal and tangential problems uncouple).
struct CattaneoMindlinSphere {
  HertzSphere hertz;
  double friction;

  // c = a (1 - Q / mu P)^(1/3) (Johnson §7.2).
  double stickRadius(double load, double tangentialLoad) const;
  // Tangential approach of distant points (Johnson §7.2):
  // 3 mu P / (16 a) ((2 - nu1)/G1 + (2 - nu2)/G2) (1 - (1 - Q / mu P)^(2/3)).
  double tangentialApproach(double load, double tangentialLoad) const;
  // Tangential displacement of the axis point at `depth` in body `body`, relative to infinity:
  // Cerruti's point load (Johnson §3.3) integrated over the Cattaneo-Mindlin traction.
  double axisTangentialDisplacement(int body, double depth, double load,
                                    double tangentialLoad) const;
  double probeTangentialApproach(double load, double tangentialLoad, double depth1,
                                 double depth2) const;
  // The Q < mu P whose probeTangentialApproach equals `approach` (bisection).
  double tangentialLoadAtProbeApproach(double load, double approach, double depth1,
                                       double depth2) const;
};

struct CattaneoMindlinCylinder {
  HertzCylinder hertz;
  double friction;

  // c = b (1 - Q / mu P)^(1/2) (Johnson §7.2), loads per unit length.
  double stickHalfWidth(double loadPerLength, double tangentialLoadPerLength) const;
};

}  // namespace cc::verification
