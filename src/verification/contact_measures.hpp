// Model-free measures of one contact pair's converged state, read from its output record: contact
// and stick areas (and the radius / half-width they imply), peak pressure, penetration, and how
// far the pressure is from uniform. They never assume the analytic solution they are compared to.
#pragma once

#include <map>

#include "mesh/mesh.hpp"
#include "records/result_records.hpp"

namespace cc::verification {

// How much of the full contact the model holds (0.25 for a quarter model with two symmetry
// planes), for plane-strain (cylinder) models its length along the axis, and where the load axis
// (a vertical line through (x0, y0); for plane strain the plane x = x0) meets the contact.
struct ModelledPart {
  double fraction = 1;
  double length = 1;
  bool planeStrain = false;
  double x0 = 0;
  double y0 = 0;
};

// Sum of the integration weights of the points in contact (state stick or slip).
double contactArea(const ContactPairRecord& pair);
// Sum of the integration weights of the points in state stick.
double stickArea(const ContactPairRecord& pair);

// Radius of the disk whose area equals the measured area of the full contact:
// sqrt(area / (pi fraction)). The error is bounded by the width of the ring of partly covered
// integration cells at the contact edge, i.e. by one element there.
double equivalentRadius(double area, const ModelledPart& part);
// Half-width of the strip with that area: area / (2 length fraction).
double equivalentHalfWidth(double area, const ModelledPart& part);

// Largest contact pressure -N over the points in contact on the master, not beside its free
// edges (N <= 0 in compression, eq. (62); ContactPairRecord::edgeShare).
double peakPressure(const ContactPairRecord& pair);
// Contact pressure -N at the point in contact on the master nearest to the load axis, where the
// Hertz pressure peaks. Unlike peakPressure it ignores spurious spikes at the contact edge.
double centrePressure(const ContactPairRecord& pair, const ModelledPart& part);
// Largest penetration -g over the points in contact on the master (as peakPressure).
double maxPenetration(const ContactPairRecord& pair);
// max |p_i - p_mean| / p_mean over the points in contact on the master, p_mean their weighted
// mean pressure: zero when the pair transmits a uniform pressure exactly (the contact patch
// test).
double pressureDeviation(const ContactPairRecord& pair);

// Tributary area of each node of a face set, the integral of its shape function over the faces
// (reference configuration): the nodal forces of a uniform pressure p are p times these.
std::map<int, double> tributaryAreas(const Mesh& mesh, const FaceSet& faces);
// The same deviation for the nodal pressures |f_a| / A_a of the slave nodes that carry a contact
// force: how unevenly the pair loads the slave body, whatever its point tractions do.
double nodalPressureDeviation(const ContactPairRecord& pair, const std::map<int, double>& areas);
// The largest |f_a| / A_a over the slave nodes: the pressure field a contour plot of the nodal
// contact forces shows. Unlike the largest point pressure it does not pick up the single points
// of an element that is only partly in contact (the Hertz sphere: +20 % at one point, -0.8 %
// at the nodes).
double peakNodalPressure(const ContactPairRecord& pair, const std::map<int, double>& areas);

}  // namespace cc::verification
