// Total-Lagrangian kinematics shared by Hex8 and the solid-shell elements: Jacobians and shape
// gradients, deformation gradient, strain-displacement (B) matrices in node-major dof order,
// internal force, material and geometric stiffness, and element status messages.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

#include "elements/element.hpp"

// Every function is a template on the node count N so that all matrices are fixed-size (no heap
// allocation inside Gauss loops). They work in any coordinate system: with Cartesian gradients
// dN/dX and F = x dN/dX they give the Cartesian Green-Lagrange strain; with parametric gradients
// dN/dxi and the current covariant basis g = x dN/dxi they give the covariant strain components
// E_ij = (g_i.g_j - G_i.G_j)/2 that ANS interpolation works with.
namespace cc::tl {

template <int N>
using NodeMatrix = Eigen::Matrix<double, 3, N>;  // column a = coordinates of node a
template <int N>
using ShapeGradients = Eigen::Matrix<double, N, 3>;  // row a = dN_a / d(coordinate i)
template <int N>
using StrainDisplacement = Eigen::Matrix<double, 6, 3 * N>;  // dE_voigt = B dx
template <int N>
using ElementVector = Eigen::Matrix<double, 3 * N, 1>;
template <int N>
using ElementMatrix = Eigen::Matrix<double, 3 * N, 3 * N>;

// Reference Jacobian J = X dN/dxi (columns are the covariant base vectors G_i). Returns det J
// and, when it is positive, fills the Cartesian gradients dN/dX = dN/dxi J^-1.
template <int N>
double cartesianGradients(const NodeMatrix<N>& X, const ShapeGradients<N>& dNdxi,
                          ShapeGradients<N>& dNdX) {
  const Eigen::Matrix3d jacobian = X * dNdxi;
  const double detJ = jacobian.determinant();
  if (detJ > 0.0) dNdX.noalias() = dNdxi * jacobian.inverse();
  return detJ;
}

// F = x dN/dX (or the current covariant basis g = x dN/dxi for parametric gradients).
template <int N>
Eigen::Matrix3d deformationGradient(const NodeMatrix<N>& x, const ShapeGradients<N>& dN) {
  return x * dN;
}

// Variation of the Green-Lagrange strain (Voigt, engineering shears) for dofs [x0 y0 z0 x1 ..]:
// dE_ii = F_i . dx_a N_a,i and d(2E_ij) = F_j . dx_a N_a,i + F_i . dx_a N_a,j (F_i = column i).
template <int N>
void strainDisplacementMatrix(const Eigen::Matrix3d& F, const ShapeGradients<N>& dN,
                              StrainDisplacement<N>& B) {
  for (int a = 0; a < N; ++a) {
    const double n1 = dN(a, 0);
    const double n2 = dN(a, 1);
    const double n3 = dN(a, 2);
    auto block = B.template middleCols<3>(3 * a);
    block.row(0) = n1 * F.col(0).transpose();
    block.row(1) = n2 * F.col(1).transpose();
    block.row(2) = n3 * F.col(2).transpose();
    block.row(3) = n1 * F.col(1).transpose() + n2 * F.col(0).transpose();
    block.row(4) = n2 * F.col(2).transpose() + n3 * F.col(1).transpose();
    block.row(5) = n1 * F.col(2).transpose() + n3 * F.col(0).transpose();
  }
}

// Green-Lagrange strain (Voigt, engineering shears) from reference and current bases given as
// matrix columns: E_ij = (g_i.g_j - G_i.G_j)/2. With G = I and g = F it is the Cartesian strain.
inline Vector6d covariantStrainVoigt(const Eigen::Matrix3d& G, const Eigen::Matrix3d& g) {
  const Eigen::Matrix3d difference = g.transpose() * g - G.transpose() * G;
  Vector6d e;
  e << 0.5 * difference(0, 0), 0.5 * difference(1, 1), 0.5 * difference(2, 2), difference(0, 1),
      difference(1, 2), difference(0, 2);
  return e;
}

// f += B^T S dV: the internal force of one Gauss point.
template <int N>
void addInternalForce(const StrainDisplacement<N>& B, const Vector6d& stress, double volume,
                      ElementVector<N>& force) {
  force.noalias() += B.transpose() * (volume * stress);
}

// f_a += F S dN_a dV: the same internal force as addInternalForce() without forming B
// (S : dE = (F S) : Grad du), for the kernels that need no B for their tangent either.
template <int N>
void addInternalForce(const Eigen::Matrix3d& F, const ShapeGradients<N>& dN,
                      const Eigen::Matrix3d& stress, double volume, ElementVector<N>& force) {
  Eigen::Map<Eigen::Matrix<double, 3, N>> nodalForces(force.data());
  nodalForces.noalias() += (volume * (F * stress)) * dN.transpose();
}

// The tangent of a hyperelastic element is symmetric, so its parts are accumulated only in the
// 3x3 node blocks K_ab with a <= b (about half the work), and mirrorUpperBlocks() fills the
// rest once after the Gauss loop.

// K_ab += B_a^T D B_b dV for a <= b: the material part of the tangent.
template <int N>
void addMaterialStiffnessUpperBlocks(const StrainDisplacement<N>& B, const Matrix6d& D,
                                     double volume, ElementMatrix<N>& K) {
  const Matrix6d weightedD = volume * D;
  for (int b = 0; b < N; ++b) {
    const Eigen::Matrix<double, 6, 3> weightedDB = weightedD * B.template middleCols<3>(3 * b);
    for (int a = 0; a <= b; ++a) {
      K.template block<3, 3>(3 * a, 3 * b).noalias() +=
          B.template middleCols<3>(3 * a).transpose() * weightedDB;
    }
  }
}

// Material and geometric parts in one pass over the node pairs, for a material tangent
// D = alpha A (x) A + 2 beta A (.) A (IsotropicTangentForm): with dE = sym(F^T du_a dN_a^T) and
// g_a = F A dN_a, K_ab += [alpha g_a g_b^T + beta ((dN_a . A dN_b) F A F^T + g_b g_a^T)
// + (dN_a . S dN_b) I] dV. Per node pair two 3x3 outer products, a scaled 3x3 matrix and a
// diagonal instead of B_a^T (D B_b) plus addGeometricStiffnessUpperBlocks(); F and dN as in
// strainDisplacementMatrix().
template <int N>
void addStiffnessUpperBlocks(const Eigen::Matrix3d& F, const ShapeGradients<N>& dN,
                             const IsotropicTangentForm& D, const Eigen::Matrix3d& stress,
                             double volume, ElementMatrix<N>& K) {
  const Eigen::Matrix3d FA = F * D.A;
  const Eigen::Matrix<double, 3, N> g = FA * dN.transpose();
  const Eigen::Matrix<double, 3, N> alphaG = (volume * D.alpha) * g;
  const Eigen::Matrix<double, 3, N> betaG = (volume * D.beta) * g;
  const Eigen::Matrix3d FAFt = FA * F.transpose();
  // (dN_a . beta A dN_b) and (dN_a . S dN_b), both times dV, for every node pair.
  const Eigen::Matrix<double, N, N> formWeights = dN * ((volume * D.beta) * D.A) * dN.transpose();
  const Eigen::Matrix<double, N, N> stressWeights = dN * (volume * stress) * dN.transpose();
  for (int b = 0; b < N; ++b) {
    for (int a = 0; a <= b; ++a) {
      auto block = K.template block<3, 3>(3 * a, 3 * b);
      block.noalias() += alphaG.col(a) * g.col(b).transpose() +
                         betaG.col(b) * g.col(a).transpose() + formWeights(a, b) * FAFt;
      block.diagonal().array() += stressWeights(a, b);
    }
  }
}

// K_ab += (dN_a . S dN_b) dV I_3 for a <= b: the geometric (initial stress) part of the tangent,
// from the second variation of E, with S the symmetric stress tensor in the coordinates of dN.
template <int N>
void addGeometricStiffnessUpperBlocks(const ShapeGradients<N>& dN, const Eigen::Matrix3d& stress,
                                      double volume, ElementMatrix<N>& K) {
  const Eigen::Matrix<double, N, 3> dNS = dN * (volume * stress);
  for (int b = 0; b < N; ++b) {
    for (int a = 0; a <= b; ++a) {
      K.template block<3, 3>(3 * a, 3 * b).diagonal().array() += dNS.row(a).dot(dN.row(b));
    }
  }
}

// K_ba = K_ab^T for a < b, completing a tangent accumulated in upper blocks.
template <int N>
void mirrorUpperBlocks(ElementMatrix<N>& K) {
  for (int b = 0; b < N; ++b) {
    for (int a = 0; a < b; ++a) {
      K.template block<3, 3>(3 * b, 3 * a) = K.template block<3, 3>(3 * a, 3 * b).transpose();
    }
  }
}

// Kirchhoff stress tau = F S F^T = J sigma.
inline Eigen::Matrix3d kirchhoffStress(const Eigen::Matrix3d& F, const Eigen::Matrix3d& S) {
  return F * S * F.transpose();
}

// Status messages naming the failing Gauss point; built only on the failure path.
ElementStatus invertedJacobian(const char* configuration, int gaussPoint, double determinant);
ElementStatus materialFailure(int gaussPoint, const Vector6d& strain);
ElementStatus notFinite(const char* what);

}  // namespace cc::tl
