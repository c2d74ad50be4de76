// Material interface: hyperelastic laws written in the reference configuration. Given the
// Green-Lagrange strain E they return the second Piola-Kirchhoff stress S and the material
// tangent D = dS/dE. Voigt order: 11, 22, 33, 12, 23, 13; strains carry engineering shears
// (2 E12, 2 E23, 2 E13) so that S : dE = S_v . dE_v.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <string>

namespace cc {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// The tangent of an isotropic law in the form D = alpha A (x) A + 2 beta A (.) A, with A a
// symmetric tensor and (A (.) A)_IJKL = (A_IK A_JL + A_IL A_JK) / 2 (St. Venant-Kirchhoff:
// lambda, mu, I; neo-Hooke: lambda, mu - lambda ln J, C^-1). A Hex8 forms its material
// stiffness from it node pair by node pair with 3-vectors, about half the arithmetic of
// B_a^T D B_b (elements/kinematics_common.hpp; issue 13).
struct IsotropicTangentForm {
  double alpha = 0;
  double beta = 0;
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
};

class Material {
 public:
  virtual ~Material() = default;
  virtual std::string name() const = 0;
  // Returns false if the strain is outside the law's domain (e.g. det C <= 0 for neo-Hooke).
  virtual bool evaluate(const Vector6d& strainVoigt, Vector6d& stressVoigt,
                        Matrix6d* tangent) const = 0;
  // Laws whose tangent has the IsotropicTangentForm say so and return it with the stress (the
  // same stress as evaluate(); false outside the law's domain).
  virtual bool hasIsotropicTangentForm() const { return false; }
  virtual bool evaluateWithTangentForm(const Vector6d& /*strainVoigt*/, Vector6d& /*stressVoigt*/,
                                       IsotropicTangentForm& /*tangent*/) const {
    return false;
  }
  // Stored energy per unit reference volume W(E) (S = dW/dE), for the energy balance of a run
  // (docs/output-format.md, /steps/<n>/energy). NaN for a law without a stored energy.
  virtual double strainEnergy(const Vector6d& /*strainVoigt*/) const {
    return std::numeric_limits<double>::quiet_NaN();
  }
  // Small-strain Lame constants, for penalty defaults and reference solutions.
  virtual double youngsModulus() const = 0;
  virtual double poissonRatio() const = 0;
};

// Green-Lagrange strain in Voigt notation (engineering shears) from the deformation gradient.
Vector6d greenLagrangeVoigt(const Eigen::Matrix3d& F);
// Symmetric tensor <-> Voigt stress vector (no factor 2).
Eigen::Matrix3d stressFromVoigt(const Vector6d& s);

std::unique_ptr<Material> makeStVenantKirchhoff(double youngsModulus, double poissonRatio);
std::unique_ptr<Material> makeNeoHooke(double youngsModulus, double poissonRatio);
// Decoupled neo-Hooke, W = C10 (I1bar - 3) + (J - 1)^2 / D1 (Abaqus/CalculiX), from C10 and D1
// or from the small-strain E and nu (C10 = mu/2, D1 = 2/K).
std::unique_ptr<Material> makeNeoHookeDecoupled(double c10, double d1);
std::unique_ptr<Material> makeNeoHookeDecoupledFromYoung(double youngsModulus, double poissonRatio);

}  // namespace cc
