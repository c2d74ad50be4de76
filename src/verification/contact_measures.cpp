// Contact measures computed from the per-point output of a contact pair.
#include "verification/contact_measures.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "fem/quadrature.hpp"
#include "fem/shape_functions.hpp"

namespace cc::verification {

namespace {

bool inContact(const ContactPairRecord& pair, Eigen::Index i) {
  return pair.state[i] != static_cast<int>(ContactState::Open);
}

// In contact on the master itself, not beside a free edge of it (ContactPairRecord::edgeShare):
// there a point's gap and pressure are measured to the master's extension, and its largest
// values say nothing of the contact (the slab's side nodes beside a die as wide as the slab:
// gaps 8 times those under the die, docs/verification/sliding.md, thirty-ninth session).
bool inContactOnMaster(const ContactPairRecord& pair, Eigen::Index i) {
  return inContact(pair, i) && (pair.edgeShare.size() == 0 || pair.edgeShare[i] >= 1);
}

// Accumulates the integral of every shape function of Shape over each face into `areas`.
template <typename Shape>
void addTributaryAreas(const Mesh& mesh, const FaceSet& faces, std::map<int, double>& areas) {
  constexpr int kQuadraturePoints = 3;  // exact for the (bi)quadratic integrands of flat faces
  for (Eigen::Index f = 0; f < faces.connectivity.rows(); ++f) {
    Eigen::Matrix<double, 3, Shape::kNodes> corners;
    for (int a = 0; a < Shape::kNodes; ++a)
      corners.col(a) = mesh.coordinates.col(faces.connectivity(f, a));
    for (const auto& point : gaussQuad(kQuadraturePoints)) {
      const typename Shape::Values values = Shape::values(point.xi);
      const Eigen::Matrix<double, 3, 2> tangents = corners * Shape::gradients(point.xi);
      const double area = tangents.col(0).cross(tangents.col(1)).norm() * point.weight;
      for (int a = 0; a < Shape::kNodes; ++a) areas[faces.connectivity(f, a)] += values[a] * area;
    }
  }
}

double maxRelativeDeviation(const std::vector<double>& values, double mean) {
  double deviation = 0;
  for (double value : values) deviation = std::max(deviation, std::abs(value - mean));
  return mean > 0 ? deviation / mean : 0;
}

}  // namespace

// Every point in contact, beside a free edge too: its weight there carries its share of the
// force, so the area is the one the force is spread over.
double contactArea(const ContactPairRecord& pair) {
  double area = 0;
  for (Eigen::Index i = 0; i < pair.state.size(); ++i) {
    if (inContact(pair, i)) area += pair.weight[i];
  }
  return area;
}

double stickArea(const ContactPairRecord& pair) {
  double area = 0;
  for (Eigen::Index i = 0; i < pair.state.size(); ++i) {
    if (pair.state[i] == static_cast<int>(ContactState::Stick)) area += pair.weight[i];
  }
  return area;
}

double equivalentRadius(double area, const ModelledPart& part) {
  return std::sqrt(area / (std::numbers::pi * part.fraction));
}

double equivalentHalfWidth(double area, const ModelledPart& part) {
  return area / (2 * part.length * part.fraction);
}

double peakPressure(const ContactPairRecord& pair) {
  double peak = 0;
  for (Eigen::Index i = 0; i < pair.state.size(); ++i) {
    if (inContactOnMaster(pair, i)) peak = std::max(peak, -pair.normalTraction[i]);
  }
  return peak;
}

double centrePressure(const ContactPairRecord& pair, const ModelledPart& part) {
  double nearest = std::numeric_limits<double>::infinity(), pressure = 0;
  for (Eigen::Index i = 0; i < pair.state.size(); ++i) {
    if (!inContactOnMaster(pair, i)) continue;
    const double dx = pair.position(0, i) - part.x0, dy = pair.position(1, i) - part.y0;
    const double distance = part.planeStrain ? std::abs(dx) : std::hypot(dx, dy);
    if (distance < nearest) {
      nearest = distance;
      pressure = -pair.normalTraction[i];
    }
  }
  return pressure;
}

double maxPenetration(const ContactPairRecord& pair) {
  double penetration = 0;
  for (Eigen::Index i = 0; i < pair.state.size(); ++i) {
    if (inContactOnMaster(pair, i)) penetration = std::max(penetration, -pair.gap[i]);
  }
  return penetration;
}

double pressureDeviation(const ContactPairRecord& pair) {
  double force = 0, area = 0;
  for (Eigen::Index i = 0; i < pair.state.size(); ++i) {
    if (!inContactOnMaster(pair, i)) continue;
    force -= pair.normalTraction[i] * pair.weight[i];
    area += pair.weight[i];
  }
  if (area == 0) return 0;
  std::vector<double> pressures;
  for (Eigen::Index i = 0; i < pair.state.size(); ++i) {
    if (inContactOnMaster(pair, i)) pressures.push_back(-pair.normalTraction[i]);
  }
  return maxRelativeDeviation(pressures, force / area);
}

std::map<int, double> tributaryAreas(const Mesh& mesh, const FaceSet& faces) {
  std::map<int, double> areas;
  if (faces.type == CellType::Quad9) {
    addTributaryAreas<shape::Quad9>(mesh, faces, areas);
  } else {
    addTributaryAreas<shape::Quad4>(mesh, faces, areas);
  }
  return areas;
}

double nodalPressureDeviation(const ContactPairRecord& pair, const std::map<int, double>& areas) {
  double force = 0, area = 0;
  std::vector<double> pressures;
  for (std::size_t k = 0; k < pair.slaveNodes.size(); ++k) {
    const double nodalForce = pair.slaveNodalForce.col(static_cast<Eigen::Index>(k)).norm();
    const auto tributary = areas.find(pair.slaveNodes[k]);
    if (nodalForce == 0 || tributary == areas.end()) continue;
    pressures.push_back(nodalForce / tributary->second);
    force += nodalForce;
    area += tributary->second;
  }
  return area > 0 ? maxRelativeDeviation(pressures, force / area) : 0;
}

double peakNodalPressure(const ContactPairRecord& pair, const std::map<int, double>& areas) {
  double peak = 0;
  for (std::size_t k = 0; k < pair.slaveNodes.size(); ++k) {
    const auto tributary = areas.find(pair.slaveNodes[k]);
    if (tributary == areas.end() || tributary->second <= 0) continue;
    const double nodalForce = pair.slaveNodalForce.col(static_cast<Eigen::Index>(k)).norm();
    peak = std::max(peak, nodalForce / tributary->second);
  }
  return peak;
}

}  // namespace cc::verification
