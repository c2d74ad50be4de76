// Anderson acceleration of a fixed-point iteration (see the header).
#include "contact/anderson_acceleration.hpp"

#include <Eigen/QR>

namespace cc::contact {

void AndersonAcceleration::reset() {
  started_ = false;
  imageChanges_.clear();
  residualChanges_.clear();
}

Eigen::VectorXd AndersonAcceleration::next(const Eigen::VectorXd& x, const Eigen::VectorXd& image,
                                           const Eigen::VectorXd& weights) {
  const Eigen::VectorXd residual = image - x;
  const Eigen::VectorXd root = weights.cwiseMax(0.0).cwiseSqrt();
  auto norm = [&](const Eigen::VectorXd& v) { return root.cwiseProduct(v).norm(); };
  if (depth_ <= 0) return image;
  const bool restart =
      !started_ || lastResidual_.size() != residual.size() || norm(residual) > norm(lastResidual_);
  if (restart) {
    imageChanges_.clear();
    residualChanges_.clear();
  } else {
    imageChanges_.push_back(image - lastImage_);
    residualChanges_.push_back(residual - lastResidual_);
    if (static_cast<int>(residualChanges_.size()) > depth_) {
      imageChanges_.pop_front();
      residualChanges_.pop_front();
    }
  }
  started_ = true;
  lastImage_ = image;
  lastResidual_ = residual;
  const int columns = static_cast<int>(residualChanges_.size());
  if (columns == 0) return image;
  // gamma = argmin |sqrt(w) (f - dF gamma)|; rank-revealing QR drops dependent columns.
  Eigen::MatrixXd changes(residual.size(), columns);
  for (int j = 0; j < columns; ++j) changes.col(j) = root.cwiseProduct(residualChanges_[j]);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(changes.rows(), changes.cols());
  qr.setThreshold(1e-10);
  qr.compute(changes);
  const Eigen::VectorXd gamma = qr.solve(root.cwiseProduct(residual));
  Eigen::VectorXd combined = image;
  for (int j = 0; j < columns; ++j) combined -= gamma[j] * imageChanges_[j];
  return combined;
}

}  // namespace cc::contact
