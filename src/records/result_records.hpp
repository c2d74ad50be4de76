// Records handed from the solver to the results writer: one per converged step, one per Newton
// iteration, one per cut-back. Plain data, so the writer never reaches back into the model.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cc {

// Contact state per point: the contact kernels' stick/slip/open decision, stored as is in the
// output
// ("state" dataset).
enum class ContactState : int { Open = 0, Stick = 1, Slip = 2 };

struct ContactPairRecord {
  std::string name;
  Eigen::Matrix3Xd position;  // slave point (current configuration)
  Eigen::VectorXd gap;        // g = (r_s - rho) . n, eq. (27)
  Eigen::VectorXd
      normalTraction;  // N = eps_N <g>, eq. (62) (compressive <= 0 convention as the paper)
  Eigen::Matrix3Xd tangentialTraction;  // T = T_i rho^i, Cartesian
  Eigen::VectorXi state;                // ContactState
  Eigen::VectorXd slipIncrement;        // |Delta rho| of the step while slipping
  Eigen::VectorXd accumulatedSlip;
  Eigen::VectorXd weight;  // integration weight (area) of the point
  // The share of its force a point keeps beyond a free edge of the master (edge=fade's band,
  // contact/contact_point.hpp): 1 on the master, below 1 beside it, where the gap is measured to
  // the master's extension and says nothing of a penetration. Its weight above already carries
  // the share. Written as "edge_share" (a ParaView threshold at 1 keeps the points on the
  // master); empty (a hand-built record): all 1.
  Eigen::VectorXd edgeShare;
  Eigen::Vector3d totalForce = Eigen::Vector3d::Zero();  // sum of forces on the slave side
  // Nodal contact forces on the slave nodes (node index, force), for force-ratio plots.
  std::vector<int> slaveNodes;
  Eigen::Matrix3Xd slaveNodalForce;
  // Energy of the pair (contact_pair_energy.cpp): stored penalty energy of the current state,
  // sum over points of w (N^2 / (2 eps_N) + |T|^2 / (2 eps_T)); frictional energy dissipated in
  // this step, sum of w mu |N| Delta lambda (the return mapping's slip, backward Euler); the
  // dissipation summed over the run; and the mean dissipation power of the step.
  Eigen::VectorXd stepDissipation;  // per point, this step
  double penaltyNormal = 0;         // eps_N in use (given or automatic)
  double penaltyTangential = 0;     // eps_T in use
  bool automaticPenalty = false;
  double penaltyEnergy = 0;
  double dissipation = 0;       // this step
  double dissipatedEnergy = 0;  // since the start of the run
  double dissipationPower = 0;  // dissipation / dt of this step
};

// Global energy balance of a converged step (model/energy_account.cpp): work of the loads, the
// support reactions and the moving rigid surfaces (trapezoidal rule over the steps) against the
// stored strain energy, the stored penalty energy of the contact pairs, the frictional and the
// viscous stabilisation's dissipation. balance = externalWork - strainEnergy - contactEnergy -
// dissipation - stabilizationDissipation is zero up to the step-size error of the trapezoidal
// rule and of the backward-Euler dissipations, of which quadratureBound = sum over steps of
// |(F_{n+1} - F_n) . (u_{n+1} - u_n)| / 2 (with the rigid surfaces' forces and motions, and the
// change of the viscous forces) is the estimate.
struct EnergyRecord {
  double externalWork = 0;
  double strainEnergy = 0;  // NaN if a material law has no stored energy
  double contactEnergy = 0;
  double dissipation = 0;  // since the start
  double dissipationPower = 0;
  // Work of the viscous stabilisation's forces since the start (NewtonSpec::stabilization;
  // 0 without it): dissipated, so the balance subtracts it like the friction's.
  double stabilizationDissipation = 0;
  double balance = 0;
  double quadratureBound = 0;
};

// What a run needs to continue from a converged step besides the displacement: the element
// and contact history and the load stepper's step size (written per step by the results writer,
// read back by readRestart in output/restart_io.hpp for `covcontact run --restart`).
struct RestartRecord {
  Eigen::VectorXd displacement;  // 3 * numNodes, node-major
  std::vector<std::pair<std::string, std::vector<double>>> elementHistory;  // per element set
  std::vector<std::pair<std::string, Eigen::MatrixXd>> contactHistory;      // per contact pair
  double stepFraction = 1;  // the next step's size in units of its phase's dt
  int easySteps = 0;        // consecutive easy steps counted towards regrowth
  // The step's own increment and dt, for `predictor=extrapolate` (empty when no phase
  // extrapolates): a restarted run then predicts its first step as the full run did.
  Eigen::VectorXd lastIncrement;  // 3 * numNodes, node-major
  double lastDt = 0;
  // The viscous stabilisation factor the phase chose (NewtonSpec::stabilizationShare; 0: none
  // chosen), so that a restart inside the phase goes on with it rather than choosing anew.
  double viscousFactor = 0;
  // Whether that factor came from the stiffness (NewtonSpec::stabilizationOnFailureShare before
  // any quasi-static step), which the next stabilised steps may still lower.
  bool viscousFactorFromStiffness = false;
  // NewtonSpec::stabilizationOnFailure: whether the next step starts stabilised, and the easy
  // steps counted towards leaving the stabilisation, so that a restart goes on as the run would.
  bool stabilizing = false;
  int stabilizedEasySteps = 0;
  // The energy account at the step (Model::accountEnergy), so that a continued run books its
  // work and dissipation on from there as the uninterrupted run does: the running sums, the
  // support reactions at the prescribed dofs (in DofMap order; the loads follow from the deck)
  // and per contact pair its moving rigid surface's force on the body and its dissipation.
  // Empty reactions: not stored (files written before the fifty-first session).
  struct Energy {
    double externalWork = 0, stabilizationDissipation = 0, quadratureBound = 0;
    Eigen::VectorXd reactions;
    Eigen::MatrixXd pairs;  // pairs x 4: rigid surface force (3), dissipated energy
    // A stabilised step: its C / dt and its increment (3 * numNodes), for the viscous force.
    double viscousRate = 0;
    Eigen::VectorXd viscousIncrement;
  } energy;
};

struct StepRecord {
  int step = 0;  // 1-based count of converged steps
  double time = 0;
  int iterations = 0;
  int cutbacks = 0;                                // cut-backs needed to reach this step
  const Eigen::Matrix3Xd* displacement = nullptr;  // 3 x numNodes
  const Eigen::Matrix3Xd* reaction = nullptr;      // 3 x numNodes, nonzero at Dirichlet dofs
  std::vector<std::pair<std::string, Eigen::Vector3d>> setReactions;  // summed per node set
  const Eigen::Matrix<double, 6, Eigen::Dynamic>* stress = nullptr;   // Cauchy, per element
  std::vector<ContactPairRecord> contact;
  EnergyRecord energy;
  const RestartRecord* restart = nullptr;  // optional: written to /steps/<step>/restart
};

// Contact points whose state (open/stick/slip) or master segment differs from the last Newton
// iteration (diagnostics of non-smooth residuals, issue 14), and the points in contact.
// The signature identifies the whole active set (every point's state and segment): Newton
// detects a cycle of the active set when a signature of this step comes back (newton.cpp).
struct ContactChanges {
  int state = 0;
  int segment = 0;
  int active = 0;
  std::uint64_t signature = 0;
  ContactChanges& operator+=(const ContactChanges& other) {
    state += other.state, segment += other.segment, active += other.active;
    signature = signature * 0x100000001b3ULL ^ other.signature;  // pairs in a fixed order
    return *this;
  }
};

// Contact points that a trial evaluation off a Newton iterate (the line search's) put on
// another master segment than the iterate had: crossing for the first time in this attempt of
// the step, or again (a point that crossed before: back over an edge, a hop).
struct PendingCrossings {
  int first = 0;
  int repeated = 0;
  PendingCrossings& operator+=(const PendingCrossings& other) {
    first += other.first, repeated += other.repeated;
    return *this;
  }
};

struct IterationRecord {
  int step = 0;       // the step being solved (1-based, as it will be numbered if it converges)
  int attempt = 0;    // 0 for the first try, k after k cut-backs of this step
  int iteration = 0;  // 1-based
  double time = 0;
  double residualNorm = 0;
  double relativeResidual = 0;
  double energy = 0;
  double relativeEnergy = 0;
  double wallSeconds = 0;    // since the start of the run
  ContactChanges contact{};  // since the previous iteration (iteration 1: since the last step's)
  // An iterative linear solve: the relative residual this iteration's solve was asked for
  // (Newton's forcing term) and the Krylov iterations it took; 0 for a direct solve.
  double krylovTolerance = 0;
  int krylovIterations = 0;
  // The fraction of this iteration's update the line search took (1: the whole update); 0 when
  // the update did not go through the line search.
  double lineSearchFraction = 0;
  // The sign of the determinant of this iteration's tangent (0: singular) where its direct
  // solver factorized it and could tell (TangentSolver::determinantSign): a sign that changes
  // between iterations or steps marks a limit point passed (--newton-log prints it).
  std::optional<int> determinantSign = std::nullopt;
};

struct CutbackRecord {
  int step = 0;
  double time = 0;  // target time that failed
  double newDt = 0;
  std::string reason;
};

}  // namespace cc
