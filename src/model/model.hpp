// Model: everything built from a validated ProblemSpec — the mesh, the element sets, the contact
// pairs, the DofMap with its Dirichlet conditions, the nodal loads and the assembler — behind the
// NonlinearProblem interface the solver sees. It also turns a converged state into the
// StepRecord the results writer stores. Built by buildModel(), which checks everything the deck
// refers to against the mesh and reports InputErrors at the deck's file:line.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "contact/contact_pair.hpp"
#include "fem/assembler.hpp"
#include "mesh/mesh.hpp"
#include "model/boundary_conditions.hpp"
#include "model/element_set.hpp"
#include "parallel/process_group.hpp"
#include "records/output_selection.hpp"
#include "records/result_records.hpp"
#include "solver/nonlinear_problem.hpp"
#include "spec/problem_spec.hpp"

namespace cc {

class Model : public NonlinearProblem {
 public:
  Model() = default;
  ~Model() override;

  // NonlinearProblem
  const DofMap& dofMap() const override { return dofs_; }
  const Eigen::Matrix3Xd& referenceCoordinates() const override { return mesh_.coordinates; }
  void prescribedValues(double t, Eigen::VectorXd& values) const override;
  void externalForces(double t, Eigen::VectorXd& force) const override;
  void rigidSurfaceOffsets(double t, Eigen::VectorXd& offsets) const override;
  void assemble(const AssemblyState& state, Eigen::VectorXd& internalForce,
                SystemMatrices* tangent) override;
  Augmentation augment() override;
  double stiffestPenaltyRatio() const override;
  void scalePenalties(double factor) override;
  double viscousFactorForShare(double share, double time, const Eigen::VectorXd& displacement,
                               const Eigen::VectorXd& internalForce) override;
  ViscousFactor viscousFactorForStiffness(double share, double dt) const override;
  void commitStep() override;
  void restoreStep() override;
  void rememberContactSearch() override;
  void recallContactSearch() override;
  // Connected groups of elements, each named after its element blocks (model_state.cpp).
  std::vector<BodyNodes> bodies() const override;
  std::string nodeLabel(int node) const override;
  ContactChanges takeContactChanges() override;
  PendingCrossings pendingContactCrossings() override;
  std::string describeSwitchingContact() override;
  void sumOverProcesses(Eigen::VectorXd& values) override;
  std::vector<int> nodeOwners() const override { return nodeOwner_; }

  // A run on several processes (model_distribution.cpp): partitions the nodes (Scotch),
  // gives each element to the process owning most of its nodes and the contact points of each
  // pair dealt out in turn (point k to process k mod P). Every process keeps the whole mesh and
  // state (the contact search runs everywhere); in Newton's iterations it evaluates and adds only
  // its own elements and contact points. assemble() then sums the internal force over the processes
  // and agrees on failures; once a solve has converged, augment() and commitStep() first evaluate
  // the other processes' contact points at the converged state (completeContactTrials), so that the
  // contact history and output stay whole and identical everywhere; commitStep() shares the
  // element history. A no-op on one process. Returns a line describing the partition (empty on
  // one process).
  std::string distribute(ProcessGroup& group);
  // Several processes: converged steps in which a contact point's master segment belonged to
  // another process than at the step before, summed over points and steps (diagnostics).
  long masterOwnerChanges() const { return masterOwnerChanges_; }
  // Several processes: seconds spent evaluating the other processes' contact points once per
  // converged solve (completeContactTrials; the assembler's timings do not include it).
  double contactCompletionSeconds() const { return contactCompletionSeconds_; }

  // Restart (model_state.cpp): the committed element and contact history (displacement and
  // step size are left to the caller), and its restoration. restoreHistory throws
  // std::invalid_argument naming what does not fit, e.g. when the deck or its mesh changed.
  RestartRecord saveHistory() const;
  // The energy account's part of the restart data, at the last booked step (empty before one).
  RestartRecord::Energy energyRestartData() const;
  void restoreHistory(const RestartRecord& history);

  const Mesh& mesh() const { return mesh_; }
  const ProblemSpec& spec() const { return spec_; }
  const std::vector<std::unique_ptr<ElementSet>>& elementSets() const { return elementSets_; }
  const std::vector<std::unique_ptr<contact::ContactPair>>& contactPairs() const {
    return contactPairs_;
  }
  int elementCount() const;
  int contactPointCount() const;
  const AssemblyTimings& assemblyTimings() const { return assembler_->timings(); }
  int threads() const { return assembler_->threads(); }

  // Energy balance (energy_account.cpp): called once per converged step, after commitStep, with
  // the converged displacement and internal force; stepRecord reports the running balance.
  void accountEnergy(double time, const Eigen::VectorXd& displacement,
                     const Eigen::VectorXd& internalForce);
  const EnergyRecord& energy() const { return energy_; }
  // A run continued with --restart: the sums go on from those stored at the restart step, and the
  // first step's work takes the forces stored there (its support reactions and rigid surfaces'
  // forces), as the uninterrupted run does. A file without them (written before the
  // fifty-first session): the sums start at zero and that step's work is one-sided, with its own
  // force (within its quadrature bound).
  void startEnergyAccount(double time, const Eigen::VectorXd& displacement,
                          const RestartRecord::Energy& stored = {});

  // The record of a converged step (reactions, set sums, stresses and contact as selected).
  // The returned record points into buffers owned by the model, valid until the next call.
  StepRecord stepRecord(int step, double time, int iterations, int cutbacks,
                        const Eigen::VectorXd& displacement, const Eigen::VectorXd& internalForce,
                        bool withStress);

 private:
  friend std::unique_ptr<Model> buildModel(const ProblemSpec& spec);
  void shareElementHistory();
  void countMasterOwnerChanges();
  int contactPointOwner(const contact::ContactPair& pair, std::size_t item) const;
  bool ownsContactPoint(const contact::ContactPair& pair, std::size_t item) const;
  void rememberAssemblyState(const AssemblyState& state);
  void completeContactTrials();
  // The work of the moving rigid surfaces (STAS) from the last booked state to `time`:
  // sum over pairs of the force each exerts on the body (minus its slave-side force) times the
  // surface's translation, by the trapezoidal rule; the step's quadrature bound; the forces.
  struct RigidSurfaceWork {
    double work = 0, quadratureBound = 0;
    std::vector<Eigen::Vector3d> forces;
  };
  RigidSurfaceWork rigidSurfaceWork(double time, bool previousForcesKnown) const;
  // The viscous stabilisation's work of the step ending at `current`, and its share of the
  // quadrature bound (energy_account.cpp).
  void accountViscousWork(const Eigen::Matrix3Xd& current);

  ProblemSpec spec_;
  Mesh mesh_;
  std::vector<std::unique_ptr<ElementSet>> elementSets_;
  std::vector<std::unique_ptr<contact::ContactPair>> contactPairs_;
  BoundaryConditions boundaryConditions_;
  DofMap dofs_;
  std::unique_ptr<Assembler> assembler_;
  // Node sets whose summed reaction is reported (those named by fix, prescribe and load).
  std::vector<std::string> reactionSets_;
  // Output buffers referenced by the last StepRecord.
  Eigen::Matrix3Xd displacementBuffer_, reactionBuffer_;
  Eigen::Matrix<double, 6, Eigen::Dynamic> stressBuffer_;
  // Energy account: the state of the last accounted step (zero: the unloaded start).
  EnergyRecord energy_;
  double energyTime_ = 0;
  double energyStepLength_ = 0;
  Eigen::VectorXd energyDisplacement_, energyForce_;
  // Per contact pair, the force its moving rigid surface exerted at that state (zero for the
  // others): the rigid surfaces' work is booked with the loads' (energy_account.cpp).
  std::vector<Eigen::Vector3d> energyRigidForce_;
  // The viscous stabilisation of that step, C / dt (0: none), and the displacement before it,
  // for the change of the viscous force over the next step.
  double energyViscousRate_ = 0;
  Eigen::VectorXd energyEarlierDisplacement_;
  bool energyForceKnown_ = true;  // false after a restart, until the first step is booked
  // The viscous stabilisation factor of the last assembly: that of the step being accounted,
  // whose converged state Newton evaluates last.
  double viscousFactor_ = 0;
  // Several processes (distribute()): the group, the owner of every node, and per element set
  // whether this process owns each element. group_ is null on one process.
  ProcessGroup* group_ = nullptr;
  std::vector<int> nodeOwner_;
  std::vector<std::vector<char>> ownsElement_;
  std::vector<std::vector<int>> masterOwner_;  // per pair and point at the last commit, -1 none
  long masterOwnerChanges_ = 0;
  std::uint64_t sharedPatternVersion_ = 0;  // the pattern version all processes analyzed last
  // The configuration of the last assembly, and whether the other processes' contact points
  // have been evaluated at it since (completeContactTrials).
  AssemblyState lastState_;
  Eigen::Matrix3Xd lastCurrent_, lastPrevious_;
  bool contactTrialsComplete_ = true;
  double contactCompletionSeconds_ = 0;
};

// Loads the mesh and builds the model. Throws InputError naming the deck line of whatever does
// not fit the mesh (unknown group or set, wrong element type for the mesh, contact on a volume
// group, bad expression, ...).
std::unique_ptr<Model> buildModel(const ProblemSpec& spec);

// The fields the deck's `output` line asks the results writer for.
OutputSelection outputSelection(const OutputSpec& output);

}  // namespace cc
