// DofMap: numbering of nodal degrees of freedom (3 per node, node-major) into free equations
// and prescribed (Dirichlet) values. Nodes not attached to any element are inactive: they get
// no equation, so orphan nodes (e.g. the dropped mid-layer of Hex27 -> SolidShell18) are harmless.
#pragma once

#include <vector>

namespace cc {

class DofMap {
 public:
  enum class Kind { Free, Prescribed, Inactive };

  DofMap() = default;
  // active[node]: node is attached to something; constrained[3*node+c]: Dirichlet dof.
  DofMap(const std::vector<bool>& activeNodes, const std::vector<bool>& constrainedDofs);

  int numNodes() const { return static_cast<int>(index_.size() / 3); }
  int numFree() const { return numFree_; }
  int numPrescribed() const { return numPrescribed_; }

  Kind kind(int dof) const {
    const int i = index_[dof];
    return i >= 0 ? Kind::Free : (i == kInactive ? Kind::Inactive : Kind::Prescribed);
  }
  // Free equation number of a nodal dof, or -1.
  int equation(int dof) const { return index_[dof] >= 0 ? index_[dof] : -1; }
  // Index among prescribed dofs, or -1.
  int prescribedIndex(int dof) const { return index_[dof] <= -2 ? -index_[dof] - 2 : -1; }
  const std::vector<int>& freeDofs() const { return freeDofs_; }              // equation -> dof
  const std::vector<int>& prescribedDofs() const { return prescribedDofs_; }  // index -> dof

 private:
  static constexpr int kInactive = -1;
  std::vector<int> index_;  // >= 0 free equation, -1 inactive, <= -2 prescribed -(p+2)
  std::vector<int> freeDofs_;
  std::vector<int> prescribedDofs_;
  int numFree_ = 0;
  int numPrescribed_ = 0;
};

}  // namespace cc
