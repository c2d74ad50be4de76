// Test and benchmark contribution: a structured grid of hexahedral cells whose 8 nodes are tied
// pairwise by linear axial springs (the node graph of a Hex8 mesh, symmetric stiffness).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "fem/contribution.hpp"

namespace cc::test {

// Structured grid of hexahedral cells; each cell is an item whose 8 nodes are tied pairwise by
// axial linear springs (stiffness varies by pair and cell so every entry is distinct).
class GridSprings : public Contribution {
 public:
  GridSprings(int nx, int ny, int nz) : nx_(nx), ny_(ny), nz_(nz) {
    for (int k = 0; k <= nz; ++k)
      for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) reference_.push_back(Eigen::Vector3d(i, j, k));
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          std::vector<int> cell;
          for (int c = 0; c < 8; ++c)
            cell.push_back(node(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2)));
          cells_.push_back(cell);
        }
  }
  int numNodes() const { return static_cast<int>(reference_.size()); }
  std::string name() const override { return "grid springs"; }
  std::size_t itemCount() const override { return cells_.size(); }
  std::span<const int> itemNodes(std::size_t item) const override { return cells_[item]; }

  // Stiffness of one cell: sum over node pairs of k_ab n n^T couplings, n = unit(X_b - X_a).
  Eigen::MatrixXd localStiffness(std::size_t item) const {
    Eigen::MatrixXd stiffness = Eigen::MatrixXd::Zero(24, 24);
    for (int a = 0; a < 8; ++a)
      for (int b = a + 1; b < 8; ++b) {
        const Eigen::Vector3d axis =
            (reference_[cells_[item][b]] - reference_[cells_[item][a]]).normalized();
        const double k = 1.0 + 0.1 * (a + b) + 0.01 * static_cast<double>(item);
        const Eigen::Matrix3d block = k * axis * axis.transpose();
        stiffness.block<3, 3>(3 * a, 3 * a) += block;
        stiffness.block<3, 3>(3 * b, 3 * b) += block;
        stiffness.block<3, 3>(3 * a, 3 * b) -= block;
        stiffness.block<3, 3>(3 * b, 3 * a) -= block;
      }
    return stiffness;
  }

  LocalStatus evaluate(std::size_t item, const AssemblyState& state, Eigen::VectorXd& force,
                       Eigen::MatrixXd* tangent) override {
    Eigen::VectorXd displacement(24);
    for (int a = 0; a < 8; ++a) {
      const int n = cells_[item][a];
      displacement.segment<3>(3 * a) = state.current->col(n) - state.reference->col(n);
    }
    const Eigen::MatrixXd stiffness = localStiffness(item);
    force += stiffness * displacement;
    if (tangent) *tangent += stiffness;
    return LocalStatus::success();
  }

  Eigen::Matrix3Xd referenceMatrix() const {
    Eigen::Matrix3Xd x(3, numNodes());
    for (int n = 0; n < numNodes(); ++n) x.col(n) = reference_[n];
    return x;
  }

 private:
  int node(int i, int j, int k) const { return i + (nx_ + 1) * (j + (ny_ + 1) * k); }
  int nx_, ny_, nz_;
  std::vector<Eigen::Vector3d> reference_;
  std::vector<std::vector<int>> cells_;
};

}  // namespace cc::test
