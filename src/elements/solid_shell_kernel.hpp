// The assumed-strain kernel shared by SolidShell8 and SolidShell18: covariant strains at the
// sampling points, ANS interpolation to the Gauss points, EAS condensation, force and tangent.
#pragma once

#include <Eigen/LU>
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "elements/kinematics_common.hpp"
#include "elements/solid_shell.hpp"
#include "elements/solid_shell_eas.hpp"
#include "elements/solid_shell_scheme.hpp"

namespace cc::solidshell {

// Frame choices (see solid_shell.hpp): the ANS interpolation acts on covariant components at the
// sampling points; each Gauss point maps its assumed covariant strain to Cartesian components
// with its own Jacobian (exact for homogeneous deformations, so the membrane patch test
// passes), and the Cartesian strain feeds the 3D material law unchanged.
template <class Shape, int NG>
class AssumedStrainKernel {
 public:
  static constexpr int N = Shape::kNodes;
  using Nodes = tl::NodeMatrix<N>;
  using Vector = tl::ElementVector<N>;
  using Matrix = tl::ElementMatrix<N>;
  using Scheme = AssumedStrainScheme<N, NG>;
  using Coupling = Eigen::Matrix<double, Eigen::Dynamic, 3 * N, 0, kMaxEasParameters, 3 * N>;
  // Rows of strain-displacement matrices stored contiguously: the ANS interpolation combines
  // single rows of many sampling points.
  using StrainRow = Eigen::Matrix<double, 1, 3 * N>;
  using RowMajorB = Eigen::Matrix<double, 6, 3 * N, Eigen::RowMajor>;

  AssumedStrainKernel(Scheme scheme, std::vector<EasMode> modes)
      : scheme_(std::move(scheme)), modes_(std::move(modes)) {}

  int easParameters() const { return static_cast<int>(modes_.size()); }

  // fint and, if tangent != nullptr, the tangent with the EAS parameters condensed out:
  // K = K_uu - K_ua K_aa^-1 K_au. alpha: warm start in, converged parameters out.
  ElementStatus evaluate(const Nodes& X, const Nodes& x, const Material& material, EasVector& alpha,
                         Vector& fint, Matrix* tangent) const {
    State& state = workspace();
    if (ElementStatus status = kinematics(X, x, state); !status.ok()) return status;
    EasSystem system;
    if (ElementStatus status = solveEnhancedStrains(state.eas, material, alpha, system);
        !status.ok()) {
      return status;
    }
    assemble(state, system, fint, tangent);
    if (!fint.allFinite()) return tl::notFinite("internal force");
    if (tangent != nullptr && !tangent->allFinite()) return tl::notFinite("tangent");
    return {};
  }

  // S at the Gauss points (converged EAS parameters) with their reference positions.
  ElementStatus gaussPointStresses(const Nodes& X, const Nodes& x, const Material& material,
                                   EasVector alpha, std::vector<GaussPointStress>& stresses) const {
    State& state = workspace();
    EasSystem system;
    if (ElementStatus status = kinematics(X, x, state); !status.ok()) return status;
    if (ElementStatus status = solveEnhancedStrains(state.eas, material, alpha, system);
        !status.ok()) {
      return status;
    }
    stresses.resize(NG);
    for (int g = 0; g < NG; ++g) {
      stresses[g].referencePosition = X * Shape::values(scheme_.gaussPoints[g]);
      stresses[g].secondPiola = state.eas[g].stress;
    }
    return {};
  }

  // Cauchy stress averaged over the current volume, sum tau w det J / sum det F w det J, with the
  // compatible F and the enhanced S. Quiet NaNs if the element cannot be evaluated.
  Vector6d cauchyStress(const Nodes& X, const Nodes& x, const Material& material,
                        EasVector alpha) const {
    const Vector6d failed = Vector6d::Constant(std::numeric_limits<double>::quiet_NaN());
    State& state = workspace();
    EasSystem system;
    if (!kinematics(X, x, state).ok()) return failed;
    if (!solveEnhancedStrains(state.eas, material, alpha, system).ok()) return failed;
    Eigen::Matrix3d kirchhoffIntegral = Eigen::Matrix3d::Zero();
    double currentVolume = 0.0;
    for (int g = 0; g < NG; ++g) {
      const Eigen::Matrix3d& F = state.deformationGradient[g];
      const double volume = state.eas[g].volume;
      kirchhoffIntegral += volume * tl::kirchhoffStress(F, stressFromVoigt(state.eas[g].stress));
      currentVolume += volume * F.determinant();
    }
    return voigtFromStress(kirchhoffIntegral / currentVolume);
  }

  // Stored energy, the sum of W(E_compatible + E_enhanced) w det J over the Gauss points, with
  // the enhanced strains in equilibrium with x (solved from alpha, as for the stresses): its
  // gradient in x is then the internal force. NaN if the element cannot be evaluated.
  double strainEnergy(const Nodes& X, const Nodes& x, const Material& material,
                      EasVector alpha) const {
    const double failed = std::numeric_limits<double>::quiet_NaN();
    State& state = workspace();
    EasSystem system;
    if (!kinematics(X, x, state).ok()) return failed;
    if (!solveEnhancedStrains(state.eas, material, alpha, system).ok()) return failed;
    double energy = 0.0;
    for (const EasGaussPoint& point : state.eas) {
      Vector6d strain = point.compatibleStrain;
      if (alpha.size() > 0) strain.noalias() += point.enhancement * alpha;
      energy += point.volume * material.strainEnergy(strain);
    }
    return energy;
  }

 private:
  // Everything the Gauss loop needs. The Hex18 arrays are large (~300 kB), so each thread keeps
  // one State per element type instead of allocating (and page-faulting) it on every call.
  struct State {
    std::vector<Vector6d> pointStrain;                     // covariant E at sampling points
    std::vector<std::array<StrainRow, 6>> pointB;          // covariant dE_k/dx there
    std::array<tl::StrainDisplacement<N>, NG> cartesianB;  // dE/dx at the Gauss points
    std::array<Matrix6d, NG> toCartesian;                  // T_g: covariant -> Cartesian
    std::array<Eigen::Matrix3d, NG> deformationGradient;   // compatible F (output only)
    std::array<EasGaussPoint, NG> eas;
    std::vector<Vector6d> pointStress;  // contravariant stress gathered per sampling point
  };

  static State& workspace() {
    thread_local State state;
    return state;
  }

  ElementStatus kinematics(const Nodes& X, const Nodes& x, State& state) const {
    if (!X.allFinite()) return tl::notFinite("reference coordinates");
    if (!x.allFinite()) return tl::notFinite("current coordinates");
    const Eigen::Matrix3d centreJacobian = X * scheme_.centreGradients;
    const double centreDet = centreJacobian.determinant();
    if (!(centreDet > 0.0)) {
      return {ElementStatus::Code::InvertedJacobian,
              "det J = " + std::to_string(centreDet) +
                  " at the element centre in the reference configuration"};
    }
    const Matrix6d centreToCartesian = strainTransformation(centreJacobian.inverse());

    const std::size_t numPoints = scheme_.samplingPoints.size();
    state.pointStrain.resize(numPoints);
    state.pointB.resize(numPoints);
    for (std::size_t p = 0; p < numPoints; ++p) {
      const tl::ShapeGradients<N>& dNdxi = scheme_.samplingGradients[p];
      const Eigen::Matrix3d referenceBasis = X * dNdxi;
      const Eigen::Matrix3d currentBasis = x * dNdxi;
      for (int k = 0; k < 6; ++k) {
        if (!scheme_.usedComponents[p][k]) continue;
        state.pointStrain[p][k] =
            covariantComponent<N>(k, referenceBasis, currentBasis, dNdxi, state.pointB[p][k]);
      }
    }

    for (int g = 0; g < NG; ++g) {
      const Eigen::Matrix3d jacobian = X * scheme_.samplingGradients[g];
      const double detJ = jacobian.determinant();
      if (!(detJ > 0.0)) return tl::invertedJacobian("reference", g, detJ);
      const Eigen::Matrix3d currentBasis = x * scheme_.samplingGradients[g];
      const double currentDet = currentBasis.determinant();
      if (!(currentDet > 0.0)) return tl::invertedJacobian("current", g, currentDet);
      const Eigen::Matrix3d inverseJacobian = jacobian.inverse();

      Vector6d covariantStrain = Vector6d::Zero();
      RowMajorB covariantB = RowMajorB::Zero();
      for (int k = 0; k < 6; ++k) {
        for (const InterpolationTerm& term : scheme_.terms[g][k]) {
          covariantStrain[k] += term.weight * state.pointStrain[term.point][k];
          covariantB.row(k) += term.weight * state.pointB[term.point][k];
        }
      }
      state.toCartesian[g] = strainTransformation(inverseJacobian);
      state.cartesianB[g].noalias() = state.toCartesian[g].lazyProduct(covariantB);
      state.deformationGradient[g] = currentBasis * inverseJacobian;

      EasGaussPoint& point = state.eas[g];
      point.compatibleStrain = state.toCartesian[g] * covariantStrain;
      point.volume = scheme_.gaussWeights[g] * detJ;
      // Simo-Rifai push-forward of the centre-frame modes: orthogonal to constant stresses.
      point.enhancement = ((centreDet / detJ) * centreToCartesian)
                              .lazyProduct(easModeMatrix(modes_, scheme_.gaussPoints[g]));
    }
    return {};
  }

  void assemble(const State& state, const EasSystem& system, Vector& fint, Matrix* tangent) const {
    fint.setZero();
    const int numAlpha = easParameters();
    Coupling coupling = Coupling::Zero(numAlpha, 3 * N);
    if (tangent != nullptr) tangent->setZero();
    // Contravariant stresses S^ij = T^T S, gathered per sampling point for the geometric part:
    // the second variation of sum_p w E_k(p) is that of E_k at point p.
    std::vector<Vector6d>& pointStress = workspace().pointStress;
    pointStress.assign(scheme_.samplingPoints.size(), Vector6d::Zero());
    for (int g = 0; g < NG; ++g) {
      const EasGaussPoint& point = state.eas[g];
      const tl::StrainDisplacement<N>& B = state.cartesianB[g];
      tl::addInternalForce<N>(B, point.stress, point.volume, fint);
      const tl::StrainDisplacement<N> weightedDB =
          (point.volume * point.materialTangent).lazyProduct(B);
      if (numAlpha > 0) coupling.noalias() += point.enhancement.transpose().lazyProduct(weightedDB);
      if (tangent == nullptr) continue;
      for (int b = 0; b < N; ++b) {  // K_ab += B_a^T D B_b dV for a <= b (symmetric)
        for (int a = 0; a <= b; ++a) {
          tangent->template block<3, 3>(3 * a, 3 * b).noalias() +=
              B.template middleCols<3>(3 * a).transpose() *
              weightedDB.template middleCols<3>(3 * b);
        }
      }
      const Vector6d contravariantStress = state.toCartesian[g].transpose() * point.stress;
      for (int k = 0; k < 6; ++k) {
        for (const InterpolationTerm& term : scheme_.terms[g][k]) {
          pointStress[term.point][k] += term.weight * point.volume * contravariantStress[k];
        }
      }
    }
    if (tangent != nullptr) {
      addGeometricStiffness(pointStress, *tangent);
      tl::mirrorUpperBlocks<N>(*tangent);
    }
    if (numAlpha == 0) return;
    // Static condensation of the local equations R_a + K_aa da + K_au du = 0; the force carries
    // the (round-off sized) correction of the last local residual, K_ua da = -K_ua K_aa^-1 R_a.
    const Eigen::FullPivLU<EasMatrix> factorization(system.stiffness);
    const EasVector residualCorrection = factorization.solve(system.residual);
    fint.noalias() -= coupling.transpose() * residualCorrection;
    if (tangent != nullptr) {
      const Coupling condensed = factorization.solve(coupling);
      tangent->noalias() -= coupling.transpose().lazyProduct(condensed);
    }
  }

  // K_ab += sum_p (dN_a . S_p dN_b) I_3 for a <= b: the geometric stiffness of all sampling
  // points, gathered into one N x N matrix before it is spread over the node blocks.
  void addGeometricStiffness(const std::vector<Vector6d>& pointStress, Matrix& tangent) const {
    Eigen::Matrix<double, N, N> geometric = Eigen::Matrix<double, N, N>::Zero();
    for (std::size_t p = 0; p < pointStress.size(); ++p) {
      const tl::ShapeGradients<N>& dN = scheme_.samplingGradients[p];
      const tl::ShapeGradients<N> dNS = dN * stressFromVoigt(pointStress[p]);
      geometric.noalias() += dNS.lazyProduct(dN.transpose());
    }
    for (int b = 0; b < N; ++b) {
      for (int a = 0; a <= b; ++a) {
        tangent.template block<3, 3>(3 * a, 3 * b).diagonal().array() += geometric(a, b);
      }
    }
  }

  Scheme scheme_;
  std::vector<EasMode> modes_;
};

}  // namespace cc::solidshell
