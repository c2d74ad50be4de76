// Shared helpers of the solid-shell tests: materials, central-difference tangent check, and a
// small linear solver for structured shell meshes (one element layer through the thickness).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

#include "elements/element.hpp"
#include "elements/solid_shell.hpp"
#include "fem/quadrature.hpp"
#include "fem/shape_functions.hpp"
#include "materials/material.hpp"

namespace sstest {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct NamedMaterial {
  const char* name;
  std::function<std::unique_ptr<cc::Material>(double young, double poisson)> make;
};
inline void PrintTo(const NamedMaterial& material, std::ostream* out) {
  *out << material.name;
}
inline const NamedMaterial kSvk{
    "svk", [](double E, double nu) { return cc::makeStVenantKirchhoff(E, nu); }};
inline const NamedMaterial kNeoHooke{"neo_hooke",
                                     [](double E, double nu) { return cc::makeNeoHooke(E, nu); }};

inline Matrix3d rotation(double angleDegrees, const Vector3d& axis) {
  return Eigen::AngleAxisd(angleDegrees * std::numbers::pi / 180.0, axis.normalized())
      .toRotationMatrix();
}

// fint of a pure-function element (no warm start).
inline Eigen::VectorXd internalForce(const cc::ElementKernel& element, const Eigen::Matrix3Xd& X,
                                     const Eigen::Matrix3Xd& x, const cc::Material& material) {
  Eigen::VectorXd fint;
  const cc::ElementStatus status = element.evaluate(X, x, material, {}, fint, nullptr);
  if (!status.ok()) ADD_FAILURE() << status.detail;
  return fint;
}

// |K_fd - K| / |K| with central differences of step h = eps^(1/3) L (L = element size):
// truncation h^2 |f'''| / 6 balances round-off eps |f| / h, an expected error near eps^(2/3).
inline double tangentFdError(const cc::ElementKernel& element, const Eigen::Matrix3Xd& X,
                             const Eigen::Matrix3Xd& x, const cc::Material& material,
                             double elementSize) {
  Eigen::VectorXd fint;
  Eigen::MatrixXd tangent;
  const cc::ElementStatus status = element.evaluate(X, x, material, {}, fint, &tangent);
  if (!status.ok()) ADD_FAILURE() << status.detail;
  const double step = std::cbrt(kEps) * elementSize;
  Eigen::MatrixXd fd(tangent.rows(), tangent.cols());
  for (int dof = 0; dof < tangent.cols(); ++dof) {
    Eigen::Matrix3Xd plus = x, minus = x;
    plus(dof % 3, dof / 3) += step;
    minus(dof % 3, dof / 3) -= step;
    fd.col(dof) =
        (internalForce(element, X, plus, material) - internalForce(element, X, minus, material)) /
        (2 * step);
  }
  return (fd - tangent).norm() / tangent.norm();
}

// A structured one-layer shell mesh: surface(u, v, s) maps [0,1]^2 x [-1,1] (s = thickness
// coordinate, -1 bottom, +1 top) to space; (du x dv) . ds must be positive.
struct ShellMesh {
  Eigen::Matrix3Xd nodes;
  std::vector<std::vector<int>> elements;  // Hex8 or Hex18 node order
  int pointsU = 0, pointsV = 0;            // grid points per direction on each face
  int node(int i, int j, int layer) const { return i + pointsU * (j + pointsV * layer); }
};

using SurfaceMap = std::function<Vector3d(double u, double v, double s)>;

inline ShellMesh shellMesh(int elementsU, int elementsV, bool quadratic, const SurfaceMap& map) {
  const int order = quadratic ? 2 : 1;
  ShellMesh mesh;
  mesh.pointsU = order * elementsU + 1;
  mesh.pointsV = order * elementsV + 1;
  mesh.nodes.resize(3, 2 * mesh.pointsU * mesh.pointsV);
  for (int layer = 0; layer < 2; ++layer) {
    for (int j = 0; j < mesh.pointsV; ++j) {
      for (int i = 0; i < mesh.pointsU; ++i) {
        mesh.nodes.col(mesh.node(i, j, layer)) =
            map(double(i) / (mesh.pointsU - 1), double(j) / (mesh.pointsV - 1), 2.0 * layer - 1);
      }
    }
  }
  // Corners counter-clockwise, then (Quad9) mid-edges 01 12 23 30 and centre, as grid offsets.
  const std::vector<std::array<int, 2>> linear = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<std::array<int, 2>> biquadratic = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 0},
                                                       {2, 1}, {1, 2}, {0, 1}, {1, 1}};
  const auto& faceOffsets = quadratic ? biquadratic : linear;
  for (int ej = 0; ej < elementsV; ++ej) {
    for (int ei = 0; ei < elementsU; ++ei) {
      std::vector<int> element;
      for (int layer = 0; layer < 2; ++layer) {
        for (const auto& offset : faceOffsets) {
          element.push_back(mesh.node(order * ei + offset[0], order * ej + offset[1], layer));
        }
      }
      mesh.elements.push_back(element);
    }
  }
  return mesh;
}

inline Eigen::Matrix3Xd gatherNodes(const Eigen::Matrix3Xd& coordinates,
                                    const std::vector<int>& element) {
  Eigen::Matrix3Xd local(3, static_cast<int>(element.size()));
  for (std::size_t a = 0; a < element.size(); ++a) local.col(a) = coordinates.col(element[a]);
  return local;
}

// Consistent nodal forces of a body force b per unit reference volume (3x3x3 Gauss points:
// exact for the polynomial integrands of flat elements, accurate to far below the benchmark
// tolerances on curved ones).
inline Eigen::VectorXd bodyForce(const ShellMesh& mesh, const Vector3d& b) {
  Eigen::VectorXd force = Eigen::VectorXd::Zero(3 * mesh.nodes.cols());
  for (const auto& connectivity : mesh.elements) {
    const Eigen::Matrix3Xd X = gatherNodes(mesh.nodes, connectivity);
    const bool quadratic = connectivity.size() == cc::shape::Hex18::kNodes;
    for (const auto& point : cc::gaussHex(3)) {
      const Eigen::VectorXd N = quadratic ? Eigen::VectorXd(cc::shape::Hex18::values(point.xi))
                                          : Eigen::VectorXd(cc::shape::Hex8::values(point.xi));
      const Eigen::MatrixXd dN = quadratic ? Eigen::MatrixXd(cc::shape::Hex18::gradients(point.xi))
                                           : Eigen::MatrixXd(cc::shape::Hex8::gradients(point.xi));
      const double volume = point.weight * (X * dN).determinant();
      for (std::size_t a = 0; a < connectivity.size(); ++a) {
        force.segment<3>(3 * connectivity[a]) += N[a] * volume * b;
      }
    }
  }
  return force;
}

// K u with K the assembled tangent at the reference configuration.
inline Eigen::VectorXd assembleTangentTimes(const cc::ElementKernel& element,
                                            const cc::Material& material, const ShellMesh& mesh,
                                            const Eigen::VectorXd& u) {
  Eigen::VectorXd result = Eigen::VectorXd::Zero(u.size());
  for (const auto& connectivity : mesh.elements) {
    const Eigen::Matrix3Xd X = gatherNodes(mesh.nodes, connectivity);
    Eigen::VectorXd fint, local(3 * connectivity.size());
    Eigen::MatrixXd K;
    const cc::ElementStatus status = element.evaluate(X, X, material, {}, fint, &K);
    if (!status.ok()) ADD_FAILURE() << status.detail;
    for (std::size_t a = 0; a < connectivity.size(); ++a) {
      local.segment<3>(3 * a) = u.segment<3>(3 * connectivity[a]);
    }
    const Eigen::VectorXd product = K * local;
    for (std::size_t a = 0; a < connectivity.size(); ++a) {
      result.segment<3>(3 * connectivity[a]) += product.segment<3>(3 * a);
    }
  }
  return result;
}

// Linear static solution K u = f about the reference configuration with u_d = 0 on the
// constrained dofs (dof = 3 node + component).
inline Eigen::VectorXd solveLinear(const cc::ElementKernel& element, const cc::Material& material,
                                   const ShellMesh& mesh, const Eigen::VectorXd& force,
                                   const std::vector<bool>& constrained) {
  const int numDofs = 3 * static_cast<int>(mesh.nodes.cols());
  std::vector<Eigen::Triplet<double>> triplets;
  for (const auto& connectivity : mesh.elements) {
    const Eigen::Matrix3Xd X = gatherNodes(mesh.nodes, connectivity);
    Eigen::VectorXd fint;
    Eigen::MatrixXd K;
    const cc::ElementStatus status = element.evaluate(X, X, material, {}, fint, &K);
    if (!status.ok()) ADD_FAILURE() << status.detail;
    for (int a = 0; a < K.rows(); ++a) {
      const int row = 3 * connectivity[a / 3] + a % 3;
      if (constrained[row]) continue;
      for (int b = 0; b < K.cols(); ++b) {
        const int col = 3 * connectivity[b / 3] + b % 3;
        if (!constrained[col]) triplets.emplace_back(row, col, K(a, b));
      }
    }
  }
  for (int dof = 0; dof < numDofs; ++dof) {
    if (constrained[dof]) triplets.emplace_back(dof, dof, 1.0);
  }
  Eigen::SparseMatrix<double> K(numDofs, numDofs);
  K.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::VectorXd rhs = force;
  for (int dof = 0; dof < numDofs; ++dof) {
    if (constrained[dof]) rhs[dof] = 0.0;
  }
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(K);
  if (solver.info() != Eigen::Success) ADD_FAILURE() << "factorization failed";
  return solver.solve(rhs);
}

}  // namespace sstest
