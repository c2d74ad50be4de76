// Assumed-strain schemes of the solid-shell elements: Gauss points, ANS sampling points with the
// interpolation weights of every covariant strain component, and the EAS mode definitions.
#pragma once

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "elements/kinematics_common.hpp"
#include "materials/voigt.hpp"

namespace cc::solidshell {

// Covariant strain components in Voigt order (engineering shears, as in materials/voigt.hpp).
enum Component : int { k11 = 0, k22 = 1, k33 = 2, k12 = 3, k23 = 4, k13 = 5 };

// Largest number of enhanced-strain parameters of any element; bounds the fixed-capacity
// matrices below so that the local iteration allocates nothing.
inline constexpr int kMaxEasParameters = 9;
using EasVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxEasParameters, 1>;
using EasMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxEasParameters, kMaxEasParameters>;
using EasOperator = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxEasParameters>;

// One enhanced covariant strain mode: component `component` = xi^e0 eta^e1 zeta^e2 alpha_m.
struct EasMode {
  int component;
  std::array<int, 3> exponents;
};

// A strain component at a Gauss point = sum over terms of weight * (component at point).
struct InterpolationTerm {
  int point;
  double weight;
};

// The element's quadrature and assumed-strain interpolation: Gauss point g's covariant
// component k is sum_t terms[g][k][t].weight * E_k(samplingPoints[terms[g][k][t].point]).
// The first NG sampling points are the Gauss points themselves (compatible components).
template <int N, int NG>
struct AssumedStrainScheme {
  std::array<Eigen::Vector3d, NG> gaussPoints;
  std::array<double, NG> gaussWeights{};
  std::vector<Eigen::Vector3d> samplingPoints;
  std::vector<tl::ShapeGradients<N>> samplingGradients;  // dN/dxi at each sampling point
  std::array<std::array<std::vector<InterpolationTerm>, 6>, NG> terms;
  tl::ShapeGradients<N> centreGradients;  // dN/dxi at xi = 0 (EAS frame)

  // Registers the Gauss points (call first, in order) as the first sampling points.
  void setGaussPoint(int g, const Eigen::Vector3d& xi, double weight) {
    gaussPoints[g] = xi;
    gaussWeights[g] = weight;
    samplingPoints.push_back(xi);
  }
  int addSamplingPoint(const Eigen::Vector3d& xi) {
    samplingPoints.push_back(xi);
    return static_cast<int>(samplingPoints.size()) - 1;
  }
  // Component k taken from the displacement field at the Gauss point itself.
  void useCompatible(int component) {
    for (int g = 0; g < NG; ++g) terms[g][component] = {{g, 1.0}};
  }
  // Shape gradients at the sampling points and which strain components each point supplies
  // (an ANS tying point needs one row of the strain-displacement matrix, not six); call last.
  template <class Shape>
  void finalize() {
    samplingGradients.clear();
    for (const Eigen::Vector3d& xi : samplingPoints) {
      samplingGradients.push_back(Shape::gradients(xi));
    }
    centreGradients = Shape::gradients(Eigen::Vector3d::Zero());
    usedComponents.assign(samplingPoints.size(), {});
    for (const auto& gaussPointTerms : terms) {
      for (int k = 0; k < 6; ++k) {
        for (const InterpolationTerm& term : gaussPointTerms[k]) {
          usedComponents[term.point][k] = true;
        }
      }
    }
  }
  std::vector<std::array<bool, 6>> usedComponents;  // per sampling point, set by finalize()
};

// Covariant strain component k (Voigt, engineering shears) at a point with reference and current
// bases G, g, and its row of the strain-displacement matrix: d(g_i.g_j) = dN_a,i g_j + dN_a,j g_i.
// `row` is a 1 x 3N writable Eigen expression (e.g. a row of a StrainDisplacement<N>).
template <int N, class Row>
double covariantComponent(int k, const Eigen::Matrix3d& G, const Eigen::Matrix3d& g,
                          const tl::ShapeGradients<N>& dNdxi, Row&& row) {
  const int i = kVoigtPairs[k][0];
  const int j = kVoigtPairs[k][1];
  for (int a = 0; a < N; ++a) {
    if (i == j) {
      row.template segment<3>(3 * a) = dNdxi(a, i) * g.col(i).transpose();
    } else {
      row.template segment<3>(3 * a) =
          (dNdxi(a, i) * g.col(j) + dNdxi(a, j) * g.col(i)).transpose();
    }
  }
  const double normalFactor = i == j ? 0.5 : 1.0;  // E_ii = (g_i.g_i - G_i.G_i) / 2
  return normalFactor * (g.col(i).dot(g.col(j)) - G.col(i).dot(G.col(j)));
}

// T with e_cartesian = T e_covariant (Voigt, engineering shears) for E = A^T E_cov A, where
// A = J^-1 maps Cartesian to parametric increments: E_kl = sum_ij A_ik E_ij A_jl.
inline Matrix6d strainTransformation(const Eigen::Matrix3d& inverseJacobian) {
  const Eigen::Matrix3d& A = inverseJacobian;
  Matrix6d T;
  for (int I = 0; I < 6; ++I) {
    const int k = kVoigtPairs[I][0];
    const int l = kVoigtPairs[I][1];
    const double engineeringFactor = k == l ? 0.5 : 1.0;  // the symmetric pair counts twice
    for (int J = 0; J < 6; ++J) {
      const int i = kVoigtPairs[J][0];
      const int j = kVoigtPairs[J][1];
      T(I, J) = engineeringFactor * (A(i, k) * A(j, l) + A(j, k) * A(i, l));
    }
  }
  return T;
}

// Covariant EAS interpolation M(xi): column m is mode m's unit strain at xi.
inline EasOperator easModeMatrix(std::span<const EasMode> modes, const Eigen::Vector3d& xi) {
  EasOperator M = EasOperator::Zero(6, static_cast<int>(modes.size()));
  for (std::size_t m = 0; m < modes.size(); ++m) {
    double monomial = 1.0;
    for (int d = 0; d < 3; ++d) {
      for (int power = 0; power < modes[m].exponents[d]; ++power) monomial *= xi[d];
    }
    M(modes[m].component, static_cast<int>(m)) = monomial;
  }
  return M;
}

// Lagrange polynomial weights through `nodes` at x (sum to one).
inline std::vector<double> lagrangeWeights(std::span<const double> nodes, double x) {
  std::vector<double> weights(nodes.size(), 1.0);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      if (i != j) weights[i] *= (x - nodes[j]) / (nodes[i] - nodes[j]);
    }
  }
  return weights;
}

}  // namespace cc::solidshell
