// ElementSet: the elements of one deck `elements` block as a Contribution, one item per element:
// gathers the element's reference and current coordinates, calls its ElementKernel with the
// block's material, and keeps the per-element history (EAS parameters) committed per step and
// the elements' reference volumes for the viscous stabilisation.
#pragma once

#include <memory>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "elements/element.hpp"
#include "fem/contribution.hpp"
#include "mesh/mesh.hpp"

namespace cc {

class ElementSet : public Contribution {
 public:
  ElementSet(std::string name, const ElementBlock& block, std::unique_ptr<ElementKernel> kernel,
             std::shared_ptr<const Material> material);

  std::string name() const override { return name_; }
  std::size_t itemCount() const override { return static_cast<std::size_t>(connectivity_.rows()); }
  std::span<const int> itemNodes(std::size_t item) const override {
    return {connectivity_.row(item).data(), static_cast<std::size_t>(connectivity_.cols())};
  }
  LocalStatus evaluate(std::size_t item, const AssemblyState& state, Eigen::VectorXd& force,
                       Eigen::MatrixXd* tangent) override;
  void commitStep() override { committedHistory_ = history_; }
  void restoreStep() override { history_ = committedHistory_; }

  // Restart: the committed history (historySize doubles per element, e.g. EAS parameters) and
  // its restoration as both the committed and the trial state. importHistory throws
  // std::invalid_argument if the size does not fit this set.
  const std::vector<double>& exportHistory() const { return committedHistory_; }
  void importHistory(std::span<const double> history) {
    if (history.size() != committedHistory_.size()) {
      throw std::invalid_argument("element set '" + name_ + "': history has " +
                                  std::to_string(history.size()) + " values, expected " +
                                  std::to_string(committedHistory_.size()));
    }
    committedHistory_.assign(history.begin(), history.end());
    history_ = committedHistory_;
  }

  // Volume-averaged Cauchy stress of every element at configuration x (Voigt, 6 x elements).
  Eigen::Matrix<double, 6, Eigen::Dynamic> cauchyStress(const Eigen::Matrix3Xd& reference,
                                                        const Eigen::Matrix3Xd& current) const;
  // Stored strain energy of the set at configuration x (NaN if the kernel has none).
  double strainEnergy(const Eigen::Matrix3Xd& reference, const Eigen::Matrix3Xd& current) const;
  // Work of the viscous stabilisation's forces (factor per time C / dt) over the step from
  // configuration `previous` to `current`, summed over the set.
  double viscousWork(const Eigen::Matrix3Xd& reference, const Eigen::Matrix3Xd& current,
                     const Eigen::Matrix3Xd& previous, double factorPerTime) const;
  int elementCount() const { return static_cast<int>(connectivity_.rows()); }
  // The material's Young's modulus and the set's size V^(1/3), V its elements' reference volume:
  // the scales of the set's stiffness as a whole (~ E L) and of its lumped volume (~ L^3), for a
  // viscous factor chosen from the stiffness (Model::viscousFactorForStiffness).
  double youngsModulus() const { return material_->youngsModulus(); }
  double size(const Eigen::Matrix3Xd& referenceCoordinates) const;

 private:
  void gather(std::size_t item, const Eigen::Matrix3Xd& coordinates, Eigen::Matrix3Xd& nodes) const;
  // Sum over the elements of term(e, a, b), a and b the element's nodes in the configurations
  // `first` and `second`.
  template <typename Term>
  double sumOverElements(const Eigen::Matrix3Xd& first, const Eigen::Matrix3Xd& second,
                         Term term) const;
  // The reference volume of every element (hexahedronVolume), the viscous stabilisation's lumped
  // masses: counted once, at the first stabilised evaluation or work (the reference
  // configuration never changes), by whichever of the assembly threads that call evaluate at
  // once gets there first; the others wait for it.
  const std::vector<double>& referenceVolumes(const Eigen::Matrix3Xd& referenceCoordinates) const;

  std::string name_;
  Connectivity connectivity_;
  std::vector<std::size_t> gmshTags_;
  std::unique_ptr<ElementKernel> kernel_;
  std::shared_ptr<const Material> material_;
  int historySize_ = 0;
  std::vector<double> history_;           // trial, per element historySize_ doubles
  std::vector<double> committedHistory_;  // at the last converged step
  mutable std::once_flag volumesCounted_;
  mutable std::vector<double> volumes_;  // per element, once counted (referenceVolumes)
};

}  // namespace cc
