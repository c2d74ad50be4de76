// Hex8 element: tangent against central differences of fint (large strain, large rotation),
// patch test on a distorted 2x2x2 patch, rigid-body rotations, tangent symmetry, force and
// moment equilibrium, failure reporting and the ElementKernel adapter.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <numbers>
#include <ostream>
#include <vector>

#include "elements/element.hpp"
#include "elements/hex8.hpp"
#include "elements/kinematics_common.hpp"
#include "fem/shape_functions.hpp"
#include "materials/voigt.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kYoung = 2.1e4;
constexpr double kPoisson = 0.3;
// Relative round-off level of sums over 8 Gauss points of products of O(1)-conditioned 3x3 and
// 24x24 matrices: a few hundred ulps.
constexpr double kRoundOff = 1e3 * kEps;
// Central differences of fint: truncation h^2 |f'''| / 6 against round-off eps |f| / h gives the
// optimal step h = eps^(1/3) L (L = element size, 1 here) and an expected relative error of
// about eps^(2/3) ~ 4e-11; kFdRelativeTolerance is the acceptance level.
const double kFdStep = std::cbrt(kEps);
constexpr double kFdRelativeTolerance = 1e-6;

struct NamedMaterial {
  const char* name;
  std::function<std::unique_ptr<cc::Material>()> make;
};
// Readable parameter names in gtest failure messages.
void PrintTo(const NamedMaterial& material, std::ostream* out) {
  *out << material.name;
}
const NamedMaterial kSvk{"svk", [] { return cc::makeStVenantKirchhoff(kYoung, kPoisson); }};
const NamedMaterial kNeoHooke{"neo_hooke", [] { return cc::makeNeoHooke(kYoung, kPoisson); }};

class Hex8WithMaterial : public ::testing::TestWithParam<NamedMaterial> {
 protected:
  std::unique_ptr<cc::Material> material = GetParam().make();
};
INSTANTIATE_TEST_SUITE_P(Hex8, Hex8WithMaterial, ::testing::Values(kSvk, kNeoHooke),
                         [](const auto& info) { return std::string(info.param.name); });

Matrix3d rotation(double angleDegrees, const Vector3d& axis) {
  return Eigen::AngleAxisd(angleDegrees * std::numbers::pi / 180.0, axis.normalized())
      .toRotationMatrix();
}

// Unit cube [0,1]^3 in gmsh order with every node moved: a general (non-parallelepiped) hex.
cc::Hex8Nodes distortedElement() {
  cc::Hex8Nodes offsets;
  offsets << 0.05, -0.08, 0.10, -0.03, 0.07, 0.02, -0.06, 0.04,  //
      -0.04, 0.06, 0.03, -0.09, 0.02, -0.05, 0.08, 0.01,         //
      0.07, -0.02, -0.05, 0.04, -0.06, 0.09, 0.03, -0.07;
  return 0.5 * (cc::shape::Hex8::nodeCoordinates().array() + 1.0).matrix() + offsets;
}

// Large strain (stretch 1.5, shear 0.5) plus a non-homogeneous nodal perturbation so that
// every Gauss point sees a different F.
cc::Hex8Nodes largeStrainConfiguration(const cc::Hex8Nodes& X) {
  Matrix3d F;
  F << 1.5, 0.5, 0.0, 0.0, 1.0, 0.1, 0.0, -0.1, 0.9;
  cc::Hex8Nodes perturbation;
  perturbation << 0.02, -0.03, 0.04, 0.01, -0.02, 0.03, -0.01, 0.02,  //
      0.03, 0.01, -0.02, 0.04, 0.02, -0.03, 0.01, -0.04,              //
      -0.02, 0.04, 0.01, -0.03, 0.03, 0.02, -0.04, 0.01;
  return F * X + perturbation;
}

cc::Hex8Vector internalForce(const cc::Hex8Nodes& X, const cc::Hex8Nodes& x,
                             const cc::Material& material) {
  cc::Hex8Vector fint;
  const cc::ElementStatus status = cc::evaluateHex8(X, x, material, fint, nullptr);
  EXPECT_TRUE(status.ok()) << status.detail;
  return fint;
}

double tangentFdError(const cc::Hex8Nodes& X, const cc::Hex8Nodes& x,
                      const cc::Material& material) {
  cc::Hex8Vector fint;
  cc::Hex8Matrix tangent;
  const cc::ElementStatus status = cc::evaluateHex8(X, x, material, fint, &tangent);
  EXPECT_TRUE(status.ok()) << status.detail;
  cc::Hex8Matrix fd;
  for (int dof = 0; dof < 24; ++dof) {
    cc::Hex8Nodes plus = x, minus = x;
    plus(dof % 3, dof / 3) += kFdStep;
    minus(dof % 3, dof / 3) -= kFdStep;
    fd.col(dof) =
        (internalForce(X, plus, material) - internalForce(X, minus, material)) / (2 * kFdStep);
  }
  return (fd - tangent).norm() / tangent.norm();
}

TEST_P(Hex8WithMaterial, TangentMatchesCentralDifferencesAtLargeStrain) {
  const cc::Hex8Nodes X = distortedElement();
  const double error = tangentFdError(X, largeStrainConfiguration(X), *material);
  EXPECT_LT(error, kFdRelativeTolerance);
  std::cout << "[ measured ] " << GetParam().name << " large strain |K_fd - K|/|K| = " << error
            << '\n';
}

TEST_P(Hex8WithMaterial, TangentMatchesCentralDifferencesAfterLargeRotation) {
  const cc::Hex8Nodes X = distortedElement();
  const Matrix3d R = rotation(120.0, Vector3d(1.0, -2.0, 0.7));
  const cc::Hex8Nodes x = (R * largeStrainConfiguration(X)).colwise() + Vector3d(0.3, -1.2, 2.0);
  const double error = tangentFdError(X, x, *material);
  EXPECT_LT(error, kFdRelativeTolerance);
  std::cout << "[ measured ] " << GetParam().name
            << " strain + 120 deg rotation |K_fd - K|/|K| = " << error << '\n';
}

TEST_P(Hex8WithMaterial, TangentIsSymmetric) {
  const cc::Hex8Nodes X = distortedElement();
  cc::Hex8Vector fint;
  cc::Hex8Matrix tangent;
  ASSERT_TRUE(cc::evaluateHex8(X, largeStrainConfiguration(X), *material, fint, &tangent).ok());
  EXPECT_LT((tangent - tangent.transpose()).norm(), kRoundOff * tangent.norm());
}

// Resultant force and moment of fint vanish for any deformation: fint is the variation of an
// energy that is invariant under rigid translations and rotations of x.
TEST_P(Hex8WithMaterial, InternalForcesAreInEquilibrium) {
  const cc::Hex8Nodes X = distortedElement();
  const Matrix3d R = rotation(37.0, Vector3d(0.2, 1.0, -0.4));
  for (const cc::Hex8Nodes& x : {largeStrainConfiguration(X), cc::Hex8Nodes(R * X * 0.8)}) {
    const cc::Hex8Vector fint = internalForce(X, x, *material);
    const Eigen::Map<const cc::Hex8Nodes> nodalForces(fint.data());
    Vector3d resultant = Vector3d::Zero();
    Vector3d moment = Vector3d::Zero();
    for (int a = 0; a < 8; ++a) {
      resultant += nodalForces.col(a);
      moment += x.col(a).cross(nodalForces.col(a));
    }
    const double forceScale = fint.cwiseAbs().maxCoeff();
    ASSERT_GT(forceScale, 0.0);
    EXPECT_LT(resultant.norm(), kRoundOff * forceScale);
    EXPECT_LT(moment.norm(), kRoundOff * forceScale * x.cwiseAbs().maxCoeff());
  }
}

TEST_P(Hex8WithMaterial, RigidRotationGivesNoForceAndNoStress) {
  const cc::Hex8Nodes X = distortedElement();
  const Matrix3d R = rotation(90.0, Vector3d(1.0, 1.0, -2.0));
  const cc::Hex8Nodes x = (R * X).colwise() + Vector3d(5.0, -3.0, 1.0);
  // Natural scales: stresses ~ E, nodal forces ~ E L^2 with L = 1.
  EXPECT_LT(internalForce(X, x, *material).norm(), kRoundOff * kYoung);
  EXPECT_LT(cc::hex8CauchyStress(X, x, *material).norm(), kRoundOff * kYoung);
}

TEST_P(Hex8WithMaterial, CauchyStressRotatesWithTheConfiguration) {
  const cc::Hex8Nodes X = distortedElement();
  const cc::Hex8Nodes x = largeStrainConfiguration(X);
  const Matrix3d R = rotation(90.0, Vector3d(-1.0, 2.0, 1.0));
  const Matrix3d cauchy = cc::stressFromVoigt(cc::hex8CauchyStress(X, x, *material));
  const Matrix3d rotated = cc::stressFromVoigt(cc::hex8CauchyStress(X, R * x, *material));
  EXPECT_LT((rotated - R * cauchy * R.transpose()).norm(), kRoundOff * cauchy.norm());
}

// A law that rejects every strain, to exercise the MaterialFailure path.
class RejectingMaterial final : public cc::Material {
 public:
  std::string name() const override { return "rejecting"; }
  bool evaluate(const cc::Vector6d&, cc::Vector6d&, cc::Matrix6d*) const override { return false; }
  double youngsModulus() const override { return kYoung; }
  double poissonRatio() const override { return kPoisson; }
};

// The material stiffness from the IsotropicTangentForm (3-vectors per node pair, issue 13) is the
// B_a^T D B_b of the general path with the law's own 6x6 tangent, to round-off, at a large
// strain of a distorted element; the stress of both evaluations is the same. So are the one-pass
// material + geometric stiffness and the internal force without B that Hex8 uses.
TEST_P(Hex8WithMaterial, TangentFormGivesTheMaterialStiffnessOfTheVoigtTangent) {
  ASSERT_TRUE(material->hasIsotropicTangentForm());
  const cc::Hex8Nodes X = distortedElement();
  const cc::Hex8Nodes x = largeStrainConfiguration(X);
  const cc::shape::Hex8::Gradients dNdxi = cc::shape::Hex8::gradients(Vector3d(-0.5, 0.1, 0.4));
  cc::tl::ShapeGradients<8> dNdX;
  ASSERT_GT(cc::tl::cartesianGradients<8>(X, dNdxi, dNdX), 0.0);
  const Matrix3d F = cc::tl::deformationGradient<8>(x, dNdX);
  const cc::Vector6d strain = cc::greenLagrangeVoigt(F);
  cc::Vector6d stress, formStress;
  cc::Matrix6d D;
  cc::IsotropicTangentForm form;
  ASSERT_TRUE(material->evaluate(strain, stress, &D));
  ASSERT_TRUE(material->evaluateWithTangentForm(strain, formStress, form));
  EXPECT_LT((formStress - stress).norm(), kRoundOff * stress.norm());
  cc::tl::StrainDisplacement<8> B;
  cc::tl::strainDisplacementMatrix<8>(F, dNdX, B);
  cc::Hex8Matrix general = cc::Hex8Matrix::Zero(), byForm = cc::Hex8Matrix::Zero();
  cc::tl::addMaterialStiffnessUpperBlocks<8>(B, D, 0.7, general);
  // With zero stress the one-pass function gives the material part alone.
  cc::tl::addStiffnessUpperBlocks<8>(F, dNdX, form, Matrix3d::Zero(), 0.7, byForm);
  cc::tl::mirrorUpperBlocks<8>(general);
  cc::tl::mirrorUpperBlocks<8>(byForm);
  EXPECT_LT((byForm - general).norm(), kRoundOff * general.norm());
  // The one-pass material + geometric stiffness and the internal force without B give the
  // sums of the B path.
  const Matrix3d S = cc::stressFromVoigt(stress);
  cc::tl::addGeometricStiffnessUpperBlocks<8>(dNdX, S, 0.7, general);
  cc::Hex8Matrix onePass = cc::Hex8Matrix::Zero();
  cc::tl::addStiffnessUpperBlocks<8>(F, dNdX, form, S, 0.7, onePass);
  cc::tl::mirrorUpperBlocks<8>(general);  // the lower blocks again, now with the geometric part
  cc::tl::mirrorUpperBlocks<8>(onePass);
  EXPECT_LT((onePass - general).norm(), kRoundOff * general.norm());
  cc::Hex8Vector forceByB = cc::Hex8Vector::Zero(), forceByF = cc::Hex8Vector::Zero();
  cc::tl::addInternalForce<8>(B, stress, 0.7, forceByB);
  cc::tl::addInternalForce<8>(F, dNdX, S, 0.7, forceByF);
  EXPECT_LT((forceByF - forceByB).norm(), kRoundOff * forceByB.norm());
}

TEST(Hex8Failures, ReportsInvertedReferenceAndCurrentConfigurations) {
  const auto material = cc::makeNeoHooke(kYoung, kPoisson);
  const cc::Hex8Nodes X = distortedElement();
  cc::Hex8Vector fint;
  // Top and bottom faces swapped: the reference element is inside out.
  cc::Hex8Nodes swapped = X;
  swapped.leftCols<4>() = X.rightCols<4>();
  swapped.rightCols<4>() = X.leftCols<4>();
  cc::ElementStatus status = cc::evaluateHex8(swapped, swapped, *material, fint, nullptr);
  EXPECT_EQ(status.code, cc::ElementStatus::Code::InvertedJacobian);
  EXPECT_NE(status.detail.find("reference"), std::string::npos) << status.detail;
  EXPECT_NE(status.detail.find("Gauss point 0"), std::string::npos) << status.detail;
  // A mirror image has det F = -1 everywhere.
  const Matrix3d mirror = Vector3d(1.0, 1.0, -1.0).asDiagonal();
  status = cc::evaluateHex8(X, mirror * X, *material, fint, nullptr);
  EXPECT_EQ(status.code, cc::ElementStatus::Code::InvertedJacobian);
  EXPECT_NE(status.detail.find("current"), std::string::npos) << status.detail;
  EXPECT_TRUE(std::isnan(cc::hex8CauchyStress(X, mirror * X, *material)[0]));
}

TEST(Hex8Failures, ReportsNonFiniteInputAndMaterialFailure) {
  const auto material = cc::makeStVenantKirchhoff(kYoung, kPoisson);
  const cc::Hex8Nodes X = distortedElement();
  cc::Hex8Nodes x = X;
  x(1, 5) = std::numeric_limits<double>::quiet_NaN();
  cc::Hex8Vector fint;
  cc::Hex8Matrix tangent;
  EXPECT_EQ(cc::evaluateHex8(X, x, *material, fint, &tangent).code,
            cc::ElementStatus::Code::NotFinite);
  x(1, 5) = std::numeric_limits<double>::infinity();
  EXPECT_EQ(cc::evaluateHex8(X, x, *material, fint, nullptr).code,
            cc::ElementStatus::Code::NotFinite);
  const cc::ElementStatus status = cc::evaluateHex8(X, X, RejectingMaterial(), fint, &tangent);
  EXPECT_EQ(status.code, cc::ElementStatus::Code::MaterialFailure);
  EXPECT_NE(status.detail.find("Gauss point 0"), std::string::npos) << status.detail;
}

TEST(Hex8Kernel, AdapterMatchesFixedSizeKernel) {
  const auto kernel = cc::makeHex8();
  EXPECT_EQ(kernel->name(), "hex8");
  EXPECT_EQ(kernel->numNodes(), 8);
  EXPECT_EQ(kernel->historySize(), 0);
  const auto material = cc::makeNeoHooke(kYoung, kPoisson);
  const cc::Hex8Nodes X = distortedElement();
  const cc::Hex8Nodes x = largeStrainConfiguration(X);
  cc::Hex8Vector fint;
  cc::Hex8Matrix tangent;
  ASSERT_TRUE(cc::evaluateHex8(X, x, *material, fint, &tangent).ok());
  Eigen::VectorXd dynamicForce;
  Eigen::MatrixXd dynamicTangent;
  const Eigen::Matrix3Xd dynamicX = X, dynamicx = x;
  ASSERT_TRUE(
      kernel->evaluate(dynamicX, dynamicx, *material, {}, dynamicForce, &dynamicTangent).ok());
  EXPECT_EQ(dynamicForce, Eigen::VectorXd(fint));
  EXPECT_EQ(dynamicTangent, Eigen::MatrixXd(tangent));
  EXPECT_EQ(kernel->cauchyStress(dynamicX, dynamicx, *material, {}),
            cc::hex8CauchyStress(X, x, *material));
  const Eigen::Matrix3Xd sevenNodes = dynamicX.leftCols(7);
  EXPECT_THROW(kernel->evaluate(sevenNodes, sevenNodes, *material, {}, dynamicForce, nullptr),
               std::invalid_argument);
}

// The shared kinematics in parametric coordinates, as the solid shells use them for ANS: with
// G = X dN/dxi and g = x dN/dxi the strain is the covariant E_ij = G_i . E G_j, B is its exact
// variation and the geometric part is the second variation contracted with a stress.
TEST(KinematicsCommon, CovariantStrainIsPulledBackCartesianStrain) {
  const Matrix3d F = (Matrix3d() << 1.5, 0.5, 0.0, 0.0, 1.0, 0.1, 0.2, -0.1, 0.9).finished();
  EXPECT_LT(
      (cc::tl::covariantStrainVoigt(Matrix3d::Identity(), F) - cc::greenLagrangeVoigt(F)).norm(),
      kRoundOff);
  const cc::Hex8Nodes X = distortedElement();
  const cc::shape::Hex8::Gradients dNdxi = cc::shape::Hex8::gradients(Vector3d(0.3, -0.2, 0.6));
  const Matrix3d G = cc::tl::deformationGradient<8>(X, dNdxi);
  const Matrix3d g = F * G;  // homogeneous deformation x = F X
  const Matrix3d covariant = cc::strainFromVoigt(cc::tl::covariantStrainVoigt(G, g));
  const Matrix3d cartesian = cc::strainFromVoigt(cc::greenLagrangeVoigt(F));
  EXPECT_LT((covariant - G.transpose() * cartesian * G).norm(), kRoundOff * covariant.norm());
}

TEST(KinematicsCommon, ParametricBMatrixAndGeometricStiffnessMatchCentralDifferences) {
  const cc::Hex8Nodes X = distortedElement();
  const cc::Hex8Nodes x = largeStrainConfiguration(X);
  const cc::shape::Hex8::Gradients dNdxi = cc::shape::Hex8::gradients(Vector3d(-0.5, 0.1, 0.4));
  const Matrix3d G = cc::tl::deformationGradient<8>(X, dNdxi);
  auto strainAt = [&](const cc::Hex8Nodes& nodes) {
    return cc::tl::covariantStrainVoigt(G, cc::tl::deformationGradient<8>(nodes, dNdxi));
  };
  cc::Vector6d stressVoigt;  // an arbitrary fixed contravariant stress
  stressVoigt << 3.0, -1.0, 2.0, 0.5, -0.7, 1.2;
  auto forceAt = [&](const cc::Hex8Nodes& nodes) {
    cc::tl::StrainDisplacement<8> B;
    cc::tl::strainDisplacementMatrix<8>(cc::tl::deformationGradient<8>(nodes, dNdxi), dNdxi, B);
    cc::tl::ElementVector<8> force = cc::tl::ElementVector<8>::Zero();
    cc::tl::addInternalForce<8>(B, stressVoigt, 1.0, force);
    return force;
  };
  cc::tl::StrainDisplacement<8> B;
  cc::tl::strainDisplacementMatrix<8>(cc::tl::deformationGradient<8>(x, dNdxi), dNdxi, B);
  cc::Hex8Matrix geometric = cc::Hex8Matrix::Zero();
  cc::tl::addGeometricStiffnessUpperBlocks<8>(dNdxi, cc::stressFromVoigt(stressVoigt), 1.0,
                                              geometric);
  cc::tl::mirrorUpperBlocks<8>(geometric);
  cc::tl::StrainDisplacement<8> fdB;
  cc::Hex8Matrix fdGeometric;
  for (int dof = 0; dof < 24; ++dof) {
    cc::Hex8Nodes plus = x, minus = x;
    plus(dof % 3, dof / 3) += kFdStep;
    minus(dof % 3, dof / 3) -= kFdStep;
    fdB.col(dof) = (strainAt(plus) - strainAt(minus)) / (2 * kFdStep);
    fdGeometric.col(dof) = (forceAt(plus) - forceAt(minus)) / (2 * kFdStep);
  }
  EXPECT_LT((fdB - B).norm(), kFdRelativeTolerance * B.norm());
  EXPECT_LT((fdGeometric - geometric).norm(), kFdRelativeTolerance * geometric.norm());
}

}  // namespace
