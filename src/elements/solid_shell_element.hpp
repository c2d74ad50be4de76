// ElementKernel adapter of the solid-shell kernels: dynamic-size node matrices and the history
// span (the EAS parameters) in, fixed-size kernel calls inside.
#pragma once

#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

#include "elements/element.hpp"
#include "elements/solid_shell_kernel.hpp"
#include "fem/shape_functions.hpp"

namespace cc::solidshell {

template <class Shape, int NG>
class SolidShellElement final : public ElementKernel {
 public:
  using Kernel = AssumedStrainKernel<Shape, NG>;
  static constexpr int N = Kernel::N;

  SolidShellElement(std::string name, Kernel kernel)
      : name_(std::move(name)), kernel_(std::move(kernel)) {}

  std::string name() const override { return name_; }
  int numNodes() const override { return N; }
  int historySize() const override { return kernel_.easParameters(); }

  // An empty history means "no warm start": the parameters start from zero and are not kept.
  ElementStatus evaluate(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& x,
                         const Material& material, std::span<double> history, Eigen::VectorXd& fint,
                         Eigen::MatrixXd* tangent) const override {
    requireNodeCount(X, x);
    EasVector alpha = warmStart(history);
    typename Kernel::Vector force;
    auto stiffness = tangent != nullptr ? std::make_unique<typename Kernel::Matrix>() : nullptr;
    const ElementStatus status = kernel_.evaluate(X, x, material, alpha, force, stiffness.get());
    fint.resize(3 * N);
    fint = force;
    if (tangent != nullptr) {
      tangent->resize(3 * N, 3 * N);
      *tangent = *stiffness;
    }
    if (status.ok() && !history.empty()) {
      for (int m = 0; m < alpha.size(); ++m) history[m] = alpha[m];
    }
    return status;
  }

  ElementStatus gaussPointStresses(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& x,
                                   const Material& material,
                                   std::vector<GaussPointStress>& stresses) const {
    requireNodeCount(X, x);
    return kernel_.gaussPointStresses(X, x, material, EasVector::Zero(kernel_.easParameters()),
                                      stresses);
  }

  Vector6d cauchyStress(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& x,
                        const Material& material, std::span<const double> history) const override {
    requireNodeCount(X, x);
    return kernel_.cauchyStress(X, x, material, warmStart(history));
  }

  double strainEnergy(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& x,
                      const Material& material, std::span<const double> history) const override {
    requireNodeCount(X, x);
    return kernel_.strainEnergy(X, x, material, warmStart(history));
  }

 private:
  // Wrong sizes are programming errors of the caller, not user input problems.
  void requireNodeCount(const Eigen::Matrix3Xd& X, const Eigen::Matrix3Xd& x) const {
    if (X.cols() != N || x.cols() != N) {
      throw std::invalid_argument(name_ + " needs " + std::to_string(N) + " nodes, got " +
                                  std::to_string(X.cols()) + " reference and " +
                                  std::to_string(x.cols()) + " current");
    }
  }

  EasVector warmStart(std::span<const double> history) const {
    const int size = kernel_.easParameters();
    if (history.empty()) return EasVector::Zero(size);
    if (static_cast<int>(history.size()) != size) {
      throw std::invalid_argument(name_ + " history holds " + std::to_string(size) +
                                  " EAS parameters, got " + std::to_string(history.size()));
    }
    EasVector alpha(size);
    for (int m = 0; m < size; ++m) alpha[m] = history[m];
    return alpha;
  }

  std::string name_;
  Kernel kernel_;
};

// The two instantiations: 2x2x2 Gauss points for SolidShell8, 3x3x2 for SolidShell18.
using SolidShell8Element = SolidShellElement<shape::Hex8, 8>;
using SolidShell18Element = SolidShellElement<shape::Hex18, 18>;

}  // namespace cc::solidshell
