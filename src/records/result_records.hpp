// Records handed from the solver to the results writer: one per converged step, one per Newton
// iteration, one per cut-back. Plain data, so the writer never reaches back into the model.
#pragma once

#include <Eigen/Core>
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
  Eigen::VectorXd weight;                                // integration weight (area) of the point
  Eigen::Vector3d totalForce = Eigen::Vector3d::Zero();  // sum of forces on the slave side
  // Nodal contact forces on the slave nodes (node index, force), for force-ratio plots.
  std::vector<int> slaveNodes;
  Eigen::Matrix3Xd slaveNodalForce;
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
  const RestartRecord* restart = nullptr;  // optional: written to /steps/<step>/restart
};

// Contact points whose state (open/stick/slip) or master segment differs from the last Newton
// iteration (diagnostics of non-smooth residuals, issue 14), and the points in contact.
struct ContactChanges {
  int state = 0;
  int segment = 0;
  int active = 0;
  ContactChanges& operator+=(const ContactChanges& other) {
    state += other.state, segment += other.segment, active += other.active;
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
  double wallSeconds = 0;  // since the start of the run
  ContactChanges contact;  // since the previous iteration (iteration 1: since the last step's)
};

struct CutbackRecord {
  int step = 0;
  double time = 0;  // target time that failed
  double newDt = 0;
  std::string reason;
};

}  // namespace cc
