// Hex8: the 8-node trilinear total-Lagrangian hexahedron with full 2x2x2 Gauss integration (the
// reference element). makeHex8() in element.hpp wraps these fixed-size kernels.
#pragma once

#include <Eigen/Core>
#include <array>

#include "elements/element.hpp"

namespace cc {

using Hex8Nodes = Eigen::Matrix<double, 3, 8>;    // column a = node a, gmsh order
using Hex8Vector = Eigen::Matrix<double, 24, 1>;  // node-major dofs
using Hex8Matrix = Eigen::Matrix<double, 24, 24>;
inline constexpr int kHex8GaussPoints = 8;

// Internal force fint = sum_g B^T S w det J and, if tangent != nullptr, the consistent tangent
// (material + geometric part). Fails with InvertedJacobian (det J <= 0 in the reference or
// current configuration), MaterialFailure or NotFinite; outputs are then unspecified.
ElementStatus evaluateHex8(const Hex8Nodes& X, const Hex8Nodes& x, const Material& material,
                           Hex8Vector& fint, Hex8Matrix* tangent);

// Second Piola-Kirchhoff stress (Voigt) at the Gauss points, in gaussHexFixed<2>() order.
ElementStatus hex8GaussPointStresses(const Hex8Nodes& X, const Hex8Nodes& x,
                                     const Material& material,
                                     std::array<Vector6d, kHex8GaussPoints>& secondPiola);

// Cauchy stress averaged over the current volume: sum_g tau_g w det J / sum_g det F w det J
// (tau = F S F^T = det F sigma). Returns quiet NaNs if the element cannot be evaluated, so that
// output shows the failure instead of a plausible number.
Vector6d hex8CauchyStress(const Hex8Nodes& X, const Hex8Nodes& x, const Material& material);
// Integral of the stored energy W(E) over the element (2x2x2 Gauss, as the internal force).
double hex8StrainEnergy(const Hex8Nodes& X, const Hex8Nodes& x, const Material& material);

}  // namespace cc
