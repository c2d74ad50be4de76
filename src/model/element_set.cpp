// Element sets: per-element evaluation through the ElementKernel interface, with the viscous
// stabilisation's forces when a step asks for them (model/viscous_stabilization.hpp).
#include "model/element_set.hpp"

#include <fmt/format.h>

#include <cmath>

#include "model/viscous_stabilization.hpp"

namespace cc {

namespace {

FailureKind failureKindOf(ElementStatus::Code code) {
  switch (code) {
    case ElementStatus::Code::InvertedJacobian:
      return FailureKind::InvertedElement;
    case ElementStatus::Code::LocalIterationFailed:
      return FailureKind::LocalIteration;
    case ElementStatus::Code::MaterialFailure:
    case ElementStatus::Code::NotFinite:
    case ElementStatus::Code::Ok:
      break;
  }
  return FailureKind::NotFinite;
}

}  // namespace

ElementSet::ElementSet(std::string name, const ElementBlock& block,
                       std::unique_ptr<ElementKernel> kernel,
                       std::shared_ptr<const Material> material)
    : name_(std::move(name)),
      connectivity_(block.connectivity),
      gmshTags_(block.gmshElementTags),
      kernel_(std::move(kernel)),
      material_(std::move(material)),
      historySize_(kernel_->historySize()),
      history_(static_cast<std::size_t>(historySize_) * block.connectivity.rows(), 0.0),
      committedHistory_(history_) {}

void ElementSet::gather(std::size_t item, const Eigen::Matrix3Xd& coordinates,
                        Eigen::Matrix3Xd& nodes) const {
  const int count = static_cast<int>(connectivity_.cols());
  nodes.resize(3, count);
  for (int k = 0; k < count; ++k) nodes.col(k) = coordinates.col(connectivity_(item, k));
}

template <typename Term>
double ElementSet::sumOverElements(const Eigen::Matrix3Xd& first, const Eigen::Matrix3Xd& second,
                                   Term term) const {
  double sum = 0.0;
  Eigen::Matrix3Xd a, b;
  for (Eigen::Index e = 0; e < connectivity_.rows(); ++e) {
    gather(e, first, a);
    gather(e, second, b);
    sum += term(e, a, b);
  }
  return sum;
}

const std::vector<double>& ElementSet::referenceVolumes(
    const Eigen::Matrix3Xd& referenceCoordinates) const {
  std::call_once(volumesCounted_, [&] {
    std::vector<double> volumes(static_cast<std::size_t>(connectivity_.rows()));
    Eigen::Matrix3Xd reference;
    for (Eigen::Index e = 0; e < connectivity_.rows(); ++e) {
      gather(e, referenceCoordinates, reference);
      volumes[e] = hexahedronVolume(reference);
    }
    volumes_ = std::move(volumes);
  });
  return volumes_;
}

double ElementSet::size(const Eigen::Matrix3Xd& referenceCoordinates) const {
  double volume = 0;
  for (double element : referenceVolumes(referenceCoordinates)) volume += std::abs(element);
  return std::cbrt(volume);
}

LocalStatus ElementSet::evaluate(std::size_t item, const AssemblyState& state,
                                 Eigen::VectorXd& force, Eigen::MatrixXd* tangent) {
  thread_local Eigen::Matrix3Xd reference, current;
  gather(item, *state.reference, reference);
  gather(item, *state.current, current);
  std::span<double> history(history_.data() + item * historySize_, historySize_);
  const ElementStatus status =
      kernel_->evaluate(reference, current, *material_, history, force, tangent);
  if (status.ok()) {
    const double dt = state.time - state.previousTime;
    if (state.viscousFactor > 0 && dt > 0 && state.previous) {
      thread_local Eigen::Matrix3Xd previous;
      gather(item, *state.previous, previous);
      addViscousForces(referenceVolumes(*state.reference)[item], current, previous,
                       state.viscousFactor / dt, force, tangent);
    }
    return LocalStatus::success();
  }
  const std::string element = item < gmshTags_.size()
                                  ? fmt::format("gmsh element {}", gmshTags_[item])
                                  : fmt::format("element {}", item);
  return LocalStatus::failure(failureKindOf(status.code),
                              fmt::format("{} '{}': {}", element, name_, status.detail));
}

Eigen::Matrix<double, 6, Eigen::Dynamic> ElementSet::cauchyStress(
    const Eigen::Matrix3Xd& referenceCoordinates,
    const Eigen::Matrix3Xd& currentCoordinates) const {
  Eigen::Matrix<double, 6, Eigen::Dynamic> stress(6, connectivity_.rows());
  Eigen::Matrix3Xd reference, current;
  for (Eigen::Index e = 0; e < connectivity_.rows(); ++e) {
    gather(e, referenceCoordinates, reference);
    gather(e, currentCoordinates, current);
    std::span<const double> history(committedHistory_.data() + e * historySize_, historySize_);
    stress.col(e) = kernel_->cauchyStress(reference, current, *material_, history);
  }
  return stress;
}

double ElementSet::viscousWork(const Eigen::Matrix3Xd& referenceCoordinates,
                               const Eigen::Matrix3Xd& currentCoordinates,
                               const Eigen::Matrix3Xd& previousCoordinates,
                               double factorPerTime) const {
  const std::vector<double>& volumes = referenceVolumes(referenceCoordinates);
  return sumOverElements(
      currentCoordinates, previousCoordinates,
      [&](Eigen::Index e, const Eigen::Matrix3Xd& current, const Eigen::Matrix3Xd& previous) {
        return cc::viscousWork(volumes[e], current, previous, factorPerTime);
      });
}

double ElementSet::strainEnergy(const Eigen::Matrix3Xd& referenceCoordinates,
                                const Eigen::Matrix3Xd& currentCoordinates) const {
  return sumOverElements(
      referenceCoordinates, currentCoordinates,
      [&](Eigen::Index e, const Eigen::Matrix3Xd& reference, const Eigen::Matrix3Xd& current) {
        std::span<const double> history(committedHistory_.data() + e * historySize_, historySize_);
        return kernel_->strainEnergy(reference, current, *material_, history);
      });
}

}  // namespace cc
