// Viscous stabilisation of the solid elements (NewtonSpec::stabilization, deck `newton
// stabilize=C`): the artificial viscous forces C m (x - x_n) / dt at an element's nodes, with m
// = V / n the nodes' equal shares of the element's reference volume V (a lumped mass of unit
// density), and the work those forces do over a step. The element sets add them
// (model/element_set.cpp); the energy account books their work (model/energy_account.cpp).
#pragma once

#include <Eigen/Core>

namespace cc {

// Reference volume of a hexahedral element from its eight corners, exact for the trilinear map
// (2 x 2 x 2 Gauss points integrate its Jacobian determinant exactly). Hex8 and SolidShell8:
// nodes 0-7 in gmsh's order; SolidShell18: the corners 0-3 and 9-12 of its two Quad9 faces.
// Throws std::logic_error for other node counts.
double hexahedronVolume(const Eigen::Matrix3Xd& reference);

// Adds k (x_a - x_n,a) to the force and k to the tangent's diagonal at every node a of one
// element, k = factorPerTime V / n with factorPerTime = C / dt, V the element's reference volume
// `volume` (hexahedronVolume: counted once by the caller, as the reference configuration never
// changes) and n its node count, the columns of `current`. force: 3n, tangent: 3n x 3n.
void addViscousForces(double volume, const Eigen::Matrix3Xd& current,
                      const Eigen::Matrix3Xd& previous, double factorPerTime,
                      Eigen::VectorXd& force, Eigen::MatrixXd* tangent);

// The work of those forces over the step from x_n to x: the force at x (backward Euler, the
// rate of the whole step) times the increment, k sum_a |x_a - x_n,a|^2.
double viscousWork(double volume, const Eigen::Matrix3Xd& current, const Eigen::Matrix3Xd& previous,
                   double factorPerTime);

}  // namespace cc
