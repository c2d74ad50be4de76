// NonlinearProblem: what the Newton solver and the load stepper need from a model, nothing
// more. The Model implements it; the solver never knows which elements or contacts it solves.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fem/assembler.hpp"
#include "fem/dof_map.hpp"
#include "records/result_records.hpp"

namespace cc {

// The nodes of one body (a connected group of elements), named after its element blocks.
struct BodyNodes {
  std::string name;
  std::vector<int> nodes;
};

class NonlinearProblem {
 public:
  virtual ~NonlinearProblem() = default;
  virtual const DofMap& dofMap() const = 0;
  virtual const Eigen::Matrix3Xd& referenceCoordinates() const = 0;
  // Values of the prescribed dofs (DofMap::prescribedDofs order) at time t.
  virtual void prescribedValues(double t, Eigen::VectorXd& values) const = 0;
  // External nodal forces (3 * numNodes) at time t.
  virtual void externalForces(double t, Eigen::VectorXd& force) const = 0;
  // The translations of the rigid surfaces that move (3 per surface, in a fixed order) at time
  // t, which an extrapolating predictor compares from step to step (solver/drive_change.hpp).
  // Empty: none moves.
  virtual void rigidSurfaceOffsets(double /*t*/, Eigen::VectorXd& offsets) const {
    offsets.resize(0);
  }
  // Internal nodal forces (elements + contact, 3 * numNodes) and optionally the tangent.
  // Throws StepFailure when an element or contact point fails.
  virtual void assemble(const AssemblyState& state, Eigen::VectorXd& internalForce,
                        SystemMatrices* tangent) = 0;
  // Augmented-Lagrangian contact: called when Newton converged, before commitStep. Updated: a
  // contact pair changed its multipliers, solve the step again; Failed: a pair exceeded its
  // number of updates (message says which). Problems without multipliers always converge.
  struct Augmentation {
    enum class Status { Converged, Updated, Failed };
    Status status = Status::Converged;
    std::string message;
    std::string note;  // for the log: what changed beyond the multipliers (a raised penalty)
  };
  virtual Augmentation augment() { return {}; }
  // Penalty continuation (load_stepper.cpp): the largest ratio of a contact pair's penalty to
  // its automatic penalty (0: no contact pair, or none with an automatic penalty known), and a
  // factor on every pair's penalties (1: as built).
  virtual double stiffestPenaltyRatio() const { return 0; }
  virtual void scalePenalties(double /*factor*/) {}
  // NewtonSpec::stabilizationShare: the viscous stabilisation factor C for which the step that
  // converged at `time` with `displacement` and `internalForce` (not yet booked) would have
  // dissipated `share` of its work of the loads, supports and moving rigid surfaces, measured from
  // the last step the energy balance booked. 0 when that step did no work or moved no solid node.
  // Not const: on several processes it first evaluates the contact points of the other processes at
  // the converged state, for the surfaces' forces.
  virtual double viscousFactorForShare(double /*share*/, double /*time*/,
                                       const Eigen::VectorXd& /*displacement*/,
                                       const Eigen::VectorXd& /*internalForce*/) {
    return 0;
  }
  // NewtonSpec::stabilizationOnFailureShare before any step has converged without
  // stabilisation (a body that only contact will hold fails the first one): the factor C from
  // the stiffness alone, and where it comes from, for the log. factor 0: no solid elements.
  struct ViscousFactor {
    double factor = 0;
    std::string origin;
  };
  virtual ViscousFactor viscousFactorForStiffness(double /*share*/, double /*dt*/) const {
    return {};
  }
  virtual void commitStep() = 0;   // the step converged: keep its history
  virtual void restoreStep() = 0;  // the step is cut back: forget the attempt
  // The contact search state (each point's master segment and parameter): remembered at an
  // iterate whose tangent Newton solves with, recalled before every trial evaluation off that
  // iterate (line search, tangent check). The search walks from where it last stood and keeps
  // a point above a ridge of a faceted master on the segment it came from, so without this
  // the residual along a Newton direction depends on which trial was evaluated last: at a
  // ridge two segments with different normals, one linearized, the other evaluated (issue 14,
  // docs/verification/sliding.md).
  virtual void rememberContactSearch() {}
  virtual void recallContactSearch() {}
  // The bodies, for naming the rigid-body motions a singular tangent leaves free
  // (solver/rigid_body_modes.hpp). Empty: all nodes form one body.
  virtual std::vector<BodyNodes> bodies() const { return {}; }
  // How messages name a node (the mesh file's own number where there is one).
  virtual std::string nodeLabel(int node) const { return "node " + std::to_string(node); }
  // Contact points that changed state or master segment since the last call (diagnostics).
  virtual ContactChanges takeContactChanges() { return {}; }
  // The contact points on another master segment than at the last takeContactChanges(), not
  // counted as changes (the line search's trials). Collective on several processes.
  virtual PendingCrossings pendingContactCrossings() { return {}; }
  // The contact points that changed state or master segment most often in this attempt of the
  // step, by name and count, for the message of a solve that failed (empty: none kept
  // changing). Collective on several processes, like every failure decision of Newton.
  virtual std::string describeSwitchingContact() { return {}; }

  // A run on several processes (`mpirun`): assemble() returns the whole internal force on
  // every process but each process's tangent holds only the items it owns (the tangent is
  // the sum over processes; the linear solver adds the shares). A vector computed from the
  // tangent is summed here. The owner process of every node; empty on one process.
  virtual void sumOverProcesses(Eigen::VectorXd&) {}
  virtual std::vector<int> nodeOwners() const { return {}; }
};

// Receives what the stepper produces; the model and the results writer live behind it.
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  virtual void iteration(const IterationRecord&) {}
  virtual void cutback(const CutbackRecord&) {}
  // |R|/|R0| at the state the step converged to, just before stepConverged (the iteration
  // records hold the residual before each update, not after the last).
  virtual void convergedResidual(double /*relative*/) {}
  // A step converged (after commitStep). displacement and internalForce are 3 * numNodes.
  virtual void stepConverged(int step, double time, int iterations, int cutbacks,
                             const Eigen::VectorXd& displacement,
                             const Eigen::VectorXd& internalForce, bool writeOutput) = 0;
  // A line for the log: the linear solver chosen, a Krylov solve redone with a direct one.
  virtual void note(const std::string&) {}
  // Polled between iterations (SIGINT/SIGTERM handling).
  virtual bool stopRequested() const { return false; }
};

}  // namespace cc
