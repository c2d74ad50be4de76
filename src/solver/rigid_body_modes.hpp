// Diagnosis of a singular tangent: which rigid-body motions (three translations, three rotations
// about the centroid) of which body the assembled stiffness K_ff leaves unrestrained, so that a
// "singular system" failure can say what support is missing instead of only quoting a pivot.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

#include "fem/dof_map.hpp"
#include "solver/linear_solver.hpp"
#include "solver/nonlinear_problem.hpp"

namespace cc {

enum class RigidMotion {
  TranslationX,
  TranslationY,
  TranslationZ,
  RotationX,
  RotationY,
  RotationZ
};

// "translation along x", "rotation about z".
std::string describe(RigidMotion motion);

// A rigid-body motion r of one body counts as unrestrained when ||K_ff r|| is below this
// fraction of ||r|| times the largest diagonal entry of K_ff. An exactly free motion leaves only
// the round-off of the assembled sums (below 1e-13 of that scale in
// SingularSystem.FreeMotionsSitAtRoundOffAndRestrainedOnesFarAboveTheThreshold); the weakest
// restraint in input/stress (a frictionless contact holding a block against rotation) measures
// above 1e-3.
inline constexpr double kUnrestrainedMotionRatio = 1e-8;

struct RigidMotionRestraint {
  int body = 0;  // index into the bodies given
  RigidMotion motion = RigidMotion::TranslationX;
  double ratio = 0;  // ||K_ff r|| / (||r|| max_j |K_jj|); below kUnrestrainedMotionRatio: free
};

// On several processes each holds a share of K_ff (its own elements and contact points); this
// sums a vector over them (NonlinearProblem::sumOverProcesses), so that K_ff r and the diagonal
// are the whole matrix's on every process. Empty: one process.
using SumOverProcesses = std::function<void(Eigen::VectorXd&)>;

// The restraint of every rigid-body motion of every body that moves at least one free dof.
// `coordinates` is the current configuration (rotations are about each body's centroid there);
// `bodies` empty means all nodes form one body.
std::vector<RigidMotionRestraint> rigidMotionRestraints(const SparseMatrix& freeStiffness,
                                                        const DofMap& dofs,
                                                        const Eigen::Matrix3Xd& coordinates,
                                                        const std::vector<BodyNodes>& bodies,
                                                        const SumOverProcesses& sum = {});

// What a singular K_ff leaves free. `message` names the unrestrained motions, e.g.
// "unconstrained rigid-body motion: translation along x of body 'block'", or, when none is
// found, says so with the least restrained motion; `freeRigidMotion` tells the two apart (a
// free body can be held by viscous stabilisation, a mechanism inside a body cannot).
struct SingularStiffnessDiagnosis {
  std::string message;
  bool freeRigidMotion = false;
};
SingularStiffnessDiagnosis describeSingularStiffness(const SparseMatrix& freeStiffness,
                                                     const DofMap& dofs,
                                                     const Eigen::Matrix3Xd& coordinates,
                                                     const std::vector<BodyNodes>& bodies,
                                                     const SumOverProcesses& sum = {});

}  // namespace cc
