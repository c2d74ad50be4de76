// Contribution: anything that adds forces and stiffness to the global system as a list of
// small local "items" (an element, a contact point). The assembler only sees this interface:
// it never knows which element or contact kind it assembles.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <span>
#include <string>

#include "common/errors.hpp"

namespace cc {

// Configuration at which contributions are evaluated. Coordinates are 3 x numNodes.
struct AssemblyState {
  double time = 0;                              // t_{n+1}, the time being solved for
  double previousTime = 0;                      // t_n, the last converged time
  const Eigen::Matrix3Xd* reference = nullptr;  // X
  const Eigen::Matrix3Xd* current = nullptr;    // x = X + u
  const Eigen::Matrix3Xd* previous = nullptr;   // x at the last converged step
  // The step's first iterate is an extrapolation of the last step's motion (Newton's
  // extrapolating predictor), not the converged state: a rigid surface is then evaluated where
  // it stands at `time`, since the bodies have already moved with it.
  bool extrapolatedStart = false;
  // Viscous stabilisation factor C (NewtonSpec::stabilization; 0: off): the element sets add
  // C m (x - x_n) / (time - previousTime) at each node, m its share of the element's volume.
  double viscousFactor = 0;
};

struct LocalStatus {
  bool ok = true;
  FailureKind kind = FailureKind::NotFinite;
  std::string detail;  // names the element / contact point and what went wrong
  static LocalStatus success() { return {}; }
  static LocalStatus failure(FailureKind k, std::string d) { return {false, k, std::move(d)}; }
};

// What this process does with an item in a run on several processes (the model decides; a
// serial run has no filter and assembles every item). The sparsity pattern of a process holds
// only the entries of the items it assembles.
enum class ItemRole {
  Assemble,      // evaluate and add into the force vector and tangent
  EvaluateOnly,  // evaluate for its history only (another process adds it)
  Skip,          // another process owns it
};
using ItemFilter = std::function<ItemRole(std::size_t contribution, std::size_t item)>;

class Contribution {
 public:
  virtual ~Contribution() = default;
  virtual std::string name() const = 0;

  // Serial work at a new configuration before items are evaluated (contact search and
  // projection, for instance). It may change the item list; then topologyVersion() changes.
  virtual LocalStatus prepare(const AssemblyState&) { return LocalStatus::success(); }

  virtual std::size_t itemCount() const = 0;
  // Nodes of one item; its local dofs are [3*k + c] for node k of this list, c = x,y,z.
  virtual std::span<const int> itemNodes(std::size_t item) const = 0;
  // Changes whenever the node lists of the items change (the sparsity pattern must follow).
  virtual std::uint64_t topologyVersion() const { return 0; }

  // Thread-safe for distinct items. `force` (3 * nodes) is added to the global internal force
  // vector, `tangent` (optional, 3n x 3n) is d force / d x. Both arrive sized and zeroed.
  virtual LocalStatus evaluate(std::size_t item, const AssemblyState& state, Eigen::VectorXd& force,
                               Eigen::MatrixXd* tangent) = 0;

  // Whether the tangent of the last evaluation is symmetric (CHOLMOD) or not (UMFPACK).
  virtual bool tangentSymmetric() const { return true; }

  // Step history: commit when a step converged, restore the last commit when it is cut back.
  virtual void commitStep() {}
  virtual void restoreStep() {}
};

}  // namespace cc
