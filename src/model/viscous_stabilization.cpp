// Viscous stabilisation of the solid elements: lumped volumes, forces, tangent and work.
#include "model/viscous_stabilization.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cc {

namespace {

// The columns of an element's coordinates that are its eight corners, in gmsh's Hex8 order.
std::array<int, 8> cornerColumns(Eigen::Index nodes) {
  if (nodes == 8) return {0, 1, 2, 3, 4, 5, 6, 7};
  if (nodes == 18) return {0, 1, 2, 3, 9, 10, 11, 12};
  throw std::logic_error("viscous stabilisation: no corners known for an element of " +
                         std::to_string(nodes) + " nodes");
}

// k = (C / dt) V / n: the viscous coefficient of each node's equal share of the element.
double nodalViscosity(double volume, Eigen::Index nodes, double factorPerTime) {
  return factorPerTime * volume / static_cast<double>(nodes);
}

}  // namespace

double hexahedronVolume(const Eigen::Matrix3Xd& reference) {
  static constexpr std::array<std::array<double, 3>, 8> kSigns = {{{-1, -1, -1},
                                                                   {1, -1, -1},
                                                                   {1, 1, -1},
                                                                   {-1, 1, -1},
                                                                   {-1, -1, 1},
                                                                   {1, -1, 1},
                                                                   {1, 1, 1},
                                                                   {-1, 1, 1}}};
  const std::array<int, 8> corners = cornerColumns(reference.cols());
  const double g = 1.0 / std::sqrt(3.0);
  double volume = 0;
  for (int point = 0; point < 8; ++point) {
    const std::array<double, 3> xi = {kSigns[point][0] * g, kSigns[point][1] * g,
                                      kSigns[point][2] * g};
    Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();  // d X / d xi, unit Gauss weights
    for (int a = 0; a < 8; ++a) {
      const std::array<double, 3>& s = kSigns[a];
      const Eigen::Vector3d dN(s[0] * (1 + s[1] * xi[1]) * (1 + s[2] * xi[2]) / 8,
                               s[1] * (1 + s[0] * xi[0]) * (1 + s[2] * xi[2]) / 8,
                               s[2] * (1 + s[0] * xi[0]) * (1 + s[1] * xi[1]) / 8);
      jacobian.noalias() += reference.col(corners[a]) * dN.transpose();
    }
    volume += jacobian.determinant();
  }
  return volume;
}

void addViscousForces(double volume, const Eigen::Matrix3Xd& current,
                      const Eigen::Matrix3Xd& previous, double factorPerTime,
                      Eigen::VectorXd& force, Eigen::MatrixXd* tangent) {
  const double k = nodalViscosity(volume, current.cols(), factorPerTime);
  for (Eigen::Index a = 0; a < current.cols(); ++a) {
    force.segment<3>(3 * a) += k * (current.col(a) - previous.col(a));
  }
  if (tangent) tangent->diagonal().array() += k;
}

double viscousWork(double volume, const Eigen::Matrix3Xd& current, const Eigen::Matrix3Xd& previous,
                   double factorPerTime) {
  return nodalViscosity(volume, current.cols(), factorPerTime) * (current - previous).squaredNorm();
}

}  // namespace cc
