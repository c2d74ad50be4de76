// Hex8 total-Lagrangian kernel: Gauss loop over the precomputed parametric shape gradients,
// using the shared kinematics of kinematics_common.hpp, and the ElementKernel adapter.
#include "elements/hex8.hpp"

#include <limits>
#include <stdexcept>
#include <string>

#include "elements/kinematics_common.hpp"
#include "fem/quadrature.hpp"
#include "fem/shape_functions.hpp"
#include "materials/voigt.hpp"

namespace cc {
namespace {

constexpr int kNodes = 8;
constexpr int kGaussPerDirection = 2;  // full integration of the trilinear element

// Parametric shape gradients and weights at the 2x2x2 Gauss points, computed once.
struct GaussTable {
  std::array<shape::Hex8::Gradients, kHex8GaussPoints> dNdxi;
  std::array<double, kHex8GaussPoints> weight;
};

const GaussTable& gaussTable() {
  static const GaussTable table = [] {
    GaussTable t;
    const auto points = gaussHexFixed<kGaussPerDirection>();
    for (int g = 0; g < kHex8GaussPoints; ++g) {
      t.dNdxi[g] = shape::Hex8::gradients(points[g].xi);
      t.weight[g] = points[g].weight;
    }
    return t;
  }();
  return table;
}

// Kinematics of one Gauss point: Cartesian gradients, deformation gradient, Green-Lagrange
// strain and reference volume weight. Checks det J in both configurations.
struct GaussPointState {
  tl::ShapeGradients<kNodes> dNdX;
  Eigen::Matrix3d F;
  Vector6d strain;
  double volume;  // w det J
  double detF;
};

ElementStatus gaussPointKinematics(const Hex8Nodes& X, const Hex8Nodes& x, int g,
                                   GaussPointState& state) {
  const GaussTable& table = gaussTable();
  const double detJ = tl::cartesianGradients<kNodes>(X, table.dNdxi[g], state.dNdX);
  if (!(detJ > 0.0)) return tl::invertedJacobian("reference", g, detJ);
  state.F = tl::deformationGradient<kNodes>(x, state.dNdX);
  state.detF = state.F.determinant();
  if (!(state.detF > 0.0)) return tl::invertedJacobian("current", g, state.detF * detJ);
  state.strain = greenLagrangeVoigt(state.F);
  state.volume = table.weight[g] * detJ;
  return {};
}

ElementStatus checkFinite(const Hex8Nodes& X, const Hex8Nodes& x) {
  if (!X.allFinite()) return tl::notFinite("reference coordinates");
  if (!x.allFinite()) return tl::notFinite("current coordinates");
  return {};
}

}  // namespace

ElementStatus evaluateHex8(const Hex8Nodes& X, const Hex8Nodes& x, const Material& material,
                           Hex8Vector& fint, Hex8Matrix* tangent) {
  if (ElementStatus status = checkFinite(X, x); !status.ok()) return status;
  fint.setZero();
  if (tangent != nullptr) tangent->setZero();
  GaussPointState state;
  tl::StrainDisplacement<kNodes> B;
  Vector6d stress;
  Matrix6d materialTangent;
  IsotropicTangentForm tangentForm;
  const bool byForm = tangent != nullptr && material.hasIsotropicTangentForm();
  for (int g = 0; g < kHex8GaussPoints; ++g) {
    if (ElementStatus status = gaussPointKinematics(X, x, g, state); !status.ok()) return status;
    if (!(byForm ? material.evaluateWithTangentForm(state.strain, stress, tangentForm)
                 : material.evaluate(state.strain, stress, tangent ? &materialTangent : nullptr))) {
      return tl::materialFailure(g, state.strain);
    }
    const Eigen::Matrix3d stressTensor = stressFromVoigt(stress);
    tl::addInternalForce<kNodes>(state.F, state.dNdX, stressTensor, state.volume, fint);
    if (byForm) {
      tl::addStiffnessUpperBlocks<kNodes>(state.F, state.dNdX, tangentForm, stressTensor,
                                          state.volume, *tangent);
    } else if (tangent != nullptr) {
      tl::strainDisplacementMatrix<kNodes>(state.F, state.dNdX, B);
      tl::addMaterialStiffnessUpperBlocks<kNodes>(B, materialTangent, state.volume, *tangent);
      tl::addGeometricStiffnessUpperBlocks<kNodes>(state.dNdX, stressTensor, state.volume,
                                                   *tangent);
    }
  }
  if (tangent != nullptr) tl::mirrorUpperBlocks<kNodes>(*tangent);
  if (!fint.allFinite()) return tl::notFinite("internal force");
  if (tangent != nullptr && !tangent->allFinite()) return tl::notFinite("tangent");
  return {};
}

ElementStatus hex8GaussPointStresses(const Hex8Nodes& X, const Hex8Nodes& x,
                                     const Material& material,
                                     std::array<Vector6d, kHex8GaussPoints>& secondPiola) {
  if (ElementStatus status = checkFinite(X, x); !status.ok()) return status;
  GaussPointState state;
  for (int g = 0; g < kHex8GaussPoints; ++g) {
    if (ElementStatus status = gaussPointKinematics(X, x, g, state); !status.ok()) return status;
    if (!material.evaluate(state.strain, secondPiola[g], nullptr)) {
      return tl::materialFailure(g, state.strain);
    }
  }
  return {};
}

Vector6d hex8CauchyStress(const Hex8Nodes& X, const Hex8Nodes& x, const Material& material) {
  const Vector6d failed = Vector6d::Constant(std::numeric_limits<double>::quiet_NaN());
  if (!checkFinite(X, x).ok()) return failed;
  Eigen::Matrix3d kirchhoffIntegral = Eigen::Matrix3d::Zero();
  double currentVolume = 0.0;
  GaussPointState state;
  Vector6d stress;
  for (int g = 0; g < kHex8GaussPoints; ++g) {
    if (!gaussPointKinematics(X, x, g, state).ok()) return failed;
    if (!material.evaluate(state.strain, stress, nullptr)) return failed;
    kirchhoffIntegral += state.volume * tl::kirchhoffStress(state.F, stressFromVoigt(stress));
    currentVolume += state.volume * state.detF;
  }
  return voigtFromStress(kirchhoffIntegral / currentVolume);
}

double hex8StrainEnergy(const Hex8Nodes& X, const Hex8Nodes& x, const Material& material) {
  if (!checkFinite(X, x).ok()) return std::numeric_limits<double>::quiet_NaN();
  double energy = 0.0;
  GaussPointState state;
  for (int g = 0; g < kHex8GaussPoints; ++g) {
    if (!gaussPointKinematics(X, x, g, state).ok()) return std::numeric_limits<double>::quiet_NaN();
    energy += state.volume * material.strainEnergy(state.strain);
  }
  return energy;
}

namespace {

class Hex8Kernel final : public ElementKernel {
 public:
  std::string name() const override { return "hex8"; }
  int numNodes() const override { return kNodes; }

  ElementStatus evaluate(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& x,
                         const Material& material, std::span<double> /*history*/,
                         Eigen::VectorXd& fint, Eigen::MatrixXd* tangent) const override {
    requireEightNodes(X, x);
    Hex8Vector force;
    Hex8Matrix stiffness;
    const ElementStatus status =
        evaluateHex8(X, x, material, force, tangent != nullptr ? &stiffness : nullptr);
    fint.resize(3 * kNodes);  // no reallocation when the caller passes sized buffers
    fint = force;
    if (tangent != nullptr) {
      tangent->resize(3 * kNodes, 3 * kNodes);
      *tangent = stiffness;
    }
    return status;
  }

  Vector6d cauchyStress(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& x,
                        const Material& material,
                        std::span<const double> /*history*/) const override {
    requireEightNodes(X, x);
    return hex8CauchyStress(X, x, material);
  }

  double strainEnergy(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& x,
                      const Material& material,
                      std::span<const double> /*history*/) const override {
    requireEightNodes(X, x);
    return hex8StrainEnergy(X, x, material);
  }

 private:
  // A wrong node count is a programming error of the caller, not a user input problem.
  static void requireEightNodes(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& x) {
    if (X.cols() != kNodes || x.cols() != kNodes) {
      throw std::invalid_argument("hex8 needs 8 nodes, got " + std::to_string(X.cols()) +
                                  " reference and " + std::to_string(x.cols()) + " current");
    }
  }
};

}  // namespace

std::unique_ptr<ElementKernel> makeHex8() {
  return std::make_unique<Hex8Kernel>();
}

}  // namespace cc
