// Element interface: a total-Lagrangian solid element is a pure function of its nodes' reference
// and current coordinates (plus a warm-start history such as EAS parameters, which only speeds
// up its local iteration). It returns the internal force vector and the consistent tangent in
// node-major dof order [x0 y0 z0 x1 y1 z1 ...]. Hex8, SolidShell8 and SolidShell18 implement it.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <span>
#include <string>

#include "materials/material.hpp"

namespace cc {

struct ElementStatus {
  enum class Code { Ok, InvertedJacobian, MaterialFailure, NotFinite, LocalIterationFailed };
  Code code = Code::Ok;
  std::string detail;  // e.g. "det J = -0.3 at Gauss point 5"
  bool ok() const { return code == Code::Ok; }
};

class ElementKernel {
 public:
  virtual ~ElementKernel() = default;
  virtual std::string name() const = 0;
  virtual int numNodes() const = 0;
  // Doubles of per-element state kept between iterations (e.g. EAS parameters); 0 if none.
  virtual int historySize() const { return 0; }

  // X, x: 3 x numNodes reference and current coordinates. history: historySize() doubles, read
  // as the initial guess of any element-level iteration and overwritten with its converged
  // value. fint: 3*numNodes internal forces. tangent (optional): 3n x 3n d fint / d x.
  virtual ElementStatus evaluate(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& x,
                                 const Material& material, std::span<double> history,
                                 Eigen::VectorXd& fint, Eigen::MatrixXd* tangent) const = 0;

  // Volume-averaged Cauchy stress (Voigt 11,22,33,12,23,13) for output.
  virtual Vector6d cauchyStress(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& x,
                                const Material& material,
                                std::span<const double> history) const = 0;

  // Stored strain energy of the element, integral of W(E) over the reference volume, for the
  // energy balance of a run (the solid-shells: at their assumed and enhanced strains). NaN where
  // not implemented or where the material has no stored energy.
  virtual double strainEnergy(const Eigen::Matrix3Xd& /*X*/, const Eigen::Matrix3Xd& /*x*/,
                              const Material& /*material*/,
                              std::span<const double> /*history*/) const {
    return std::numeric_limits<double>::quiet_NaN();
  }
};

std::unique_ptr<ElementKernel> makeHex8();

}  // namespace cc
