// Energy balance of a run (issue 16, part 4). Work of the loads, the support reactions and the
// moving rigid surfaces, W_ext = sum over steps of (F_n + F_{n+1}) . (u_{n+1} - u_n) / 2 with
// F = f_ext + reactions, plus (R_n + R_{n+1}) . (d_{n+1} - d_n) / 2 for each rigid surface with
// translation d and contact force R on the body (the trapezoidal rule), against the stored strain
// energy of the elements, the stored energy of the contact penalty springs, the frictional
// dissipation and the viscous stabilisation's:
//   W_ext = E_strain + E_contact + D + D_stab  (+ the step-size error of the time integrations).
// The trapezoidal rule and the backward-Euler dissipation differ from the exact integrals by
// O(step^2) per step; sum |(F_{n+1} - F_n) . Delta u| / 2, the difference between the
// trapezoidal and a one-sided rule, measures that error and is reported with the balance.
// Also the viscous stabilisation factors a run chooses: from a step's work and motion, and, before
// any step has converged without stabilisation, from the stiffness alone.
#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <utility>

#include "model/model.hpp"

namespace cc {

void Model::startEnergyAccount(double time, const Eigen::VectorXd& displacement,
                               const RestartRecord::Energy& stored) {
  energyDisplacement_ = displacement;
  energyForce_.setZero(displacement.size());
  energyRigidForce_.assign(contactPairs_.size(), Eigen::Vector3d::Zero());
  energyForceKnown_ = false;
  energyTime_ = time;
  energy_ = EnergyRecord{};
  energyViscousRate_ = 0;
  energyEarlierDisplacement_.resize(0);
  const std::vector<int>& prescribed = dofs_.prescribedDofs();
  const auto pairs = static_cast<Eigen::Index>(contactPairs_.size());
  if (stored.reactions.size() != static_cast<Eigen::Index>(prescribed.size()) ||
      stored.pairs.rows() != pairs || stored.pairs.cols() != 4) {
    return;
  }
  energy_.externalWork = stored.externalWork;
  energy_.stabilizationDissipation = stored.stabilizationDissipation;
  energy_.quadratureBound = stored.quadratureBound;
  externalForces(time, energyForce_);
  for (std::size_t i = 0; i < prescribed.size(); ++i) {
    energyForce_[prescribed[i]] = stored.reactions[static_cast<Eigen::Index>(i)];
  }
  for (Eigen::Index p = 0; p < pairs; ++p) {
    energyRigidForce_[static_cast<std::size_t>(p)] = stored.pairs.row(p).head<3>().transpose();
    contactPairs_[static_cast<std::size_t>(p)]->restoreDissipatedEnergy(stored.pairs(p, 3));
  }
  if (stored.viscousRate > 0 && stored.viscousIncrement.size() == displacement.size()) {
    energyViscousRate_ = stored.viscousRate;
    energyEarlierDisplacement_ = displacement - stored.viscousIncrement;
  }
  energyForceKnown_ = true;
}

RestartRecord::Energy Model::energyRestartData() const {
  RestartRecord::Energy stored;
  const std::vector<int>& prescribed = dofs_.prescribedDofs();
  if (energyForce_.size() != 3 * static_cast<Eigen::Index>(mesh_.numNodes()) ||
      energyRigidForce_.size() != contactPairs_.size()) {
    return stored;  // no step booked yet
  }
  stored.externalWork = energy_.externalWork;
  stored.stabilizationDissipation = energy_.stabilizationDissipation;
  stored.quadratureBound = energy_.quadratureBound;
  stored.reactions.resize(static_cast<Eigen::Index>(prescribed.size()));
  for (std::size_t i = 0; i < prescribed.size(); ++i) {
    stored.reactions[static_cast<Eigen::Index>(i)] = energyForce_[prescribed[i]];
  }
  stored.pairs.resize(static_cast<Eigen::Index>(contactPairs_.size()), 4);
  for (std::size_t p = 0; p < contactPairs_.size(); ++p) {
    const auto row = static_cast<Eigen::Index>(p);
    stored.pairs.row(row).head<3>() = energyRigidForce_[p].transpose();
    stored.pairs(row, 3) = contactPairs_[p]->dissipatedEnergy();
  }
  if (energyViscousRate_ > 0 && energyEarlierDisplacement_.size() == energyDisplacement_.size()) {
    stored.viscousRate = energyViscousRate_;
    stored.viscousIncrement = energyDisplacement_ - energyEarlierDisplacement_;
  }
  return stored;
}

namespace {

// F = f_ext + reaction: the external force at the free dofs, the internal one (f_int - f_ext is
// the reaction) at the prescribed dofs.
Eigen::VectorXd loadAndSupportForce(const Model& model, double time,
                                    const Eigen::VectorXd& internalForce) {
  Eigen::VectorXd force;
  model.externalForces(time, force);
  for (int dof : model.dofMap().prescribedDofs()) force[dof] = internalForce[dof];
  return force;
}

}  // namespace

// A STAS deck whose rigid die drives the model puts all its work in through the die: without
// this term its external work was zero, its balance the negative of the stored energy, and a
// factor chosen from the work (stabilize_share) zero.
Model::RigidSurfaceWork Model::rigidSurfaceWork(double time, bool previousForcesKnown) const {
  RigidSurfaceWork result;
  result.forces.assign(contactPairs_.size(), Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < contactPairs_.size(); ++i) {
    const contact::ContactPair& pair = *contactPairs_[i];
    const std::optional<Eigen::Vector3d> now = pair.surfaceOffsetAt(time);
    if (!now) continue;
    const Eigen::Vector3d motion = *now - *pair.surfaceOffsetAt(energyTime_);
    result.forces[i] = -pair.slaveSideForce();  // the rigid surface is the slave side
    const Eigen::Vector3d before = !previousForcesKnown           ? result.forces[i]
                                   : i < energyRigidForce_.size() ? energyRigidForce_[i]
                                                                  : Eigen::Vector3d::Zero();
    result.work += 0.5 * (result.forces[i] + before).dot(motion);
    result.quadratureBound += 0.5 * std::abs((result.forces[i] - before).dot(motion));
  }
  return result;
}

double Model::viscousFactorForShare(double share, double time, const Eigen::VectorXd& displacement,
                                    const Eigen::VectorXd& internalForce) {
  completeContactTrials();  // the rigid surfaces' forces need every contact point's state
  const int n = mesh_.numNodes();
  const double stepLength = time - energyTime_;
  if (!(stepLength > 0)) return 0;
  const bool booked = energyDisplacement_.size() == 3 * n;  // else the unloaded start
  const Eigen::VectorXd previousDisplacement =
      booked ? energyDisplacement_ : Eigen::VectorXd::Zero(3 * n);
  const Eigen::VectorXd force = loadAndSupportForce(*this, time, internalForce);
  // After a restart the forces at its state are not stored: the step's own force stands for
  // them (the step's work by the one-sided rule, not half of it).
  const Eigen::VectorXd previousForce = !booked             ? Eigen::VectorXd::Zero(3 * n)
                                        : energyForceKnown_ ? energyForce_
                                                            : force;
  const double work =
      std::abs(0.5 * (force + previousForce).dot(displacement - previousDisplacement) +
               rigidSurfaceWork(time, !booked || energyForceKnown_).work);
  // The dissipation at C = 1: sum_a m_a |dx_a|^2 / dt.
  const Eigen::Matrix3Xd current =
      mesh_.coordinates + Eigen::Map<const Eigen::Matrix3Xd>(displacement.data(), 3, n);
  const Eigen::Matrix3Xd previous =
      mesh_.coordinates + Eigen::Map<const Eigen::Matrix3Xd>(previousDisplacement.data(), 3, n);
  double unitDissipation = 0;
  for (const auto& set : elementSets_) {
    unitDissipation += set->viscousWork(mesh_.coordinates, current, previous, 1 / stepLength);
  }
  return work > 0 && unitDissipation > 0 ? share * work / unitDissipation : 0.0;
}

// C = share E dt / L^2, E and L = V^(1/3) an element set's Young's modulus and size. The viscous
// forces C m (x - x_n) / dt on the set's lumped volume (sum m = L^3) then stand to its stiffness
// as a whole (~ E L) as `share`, so a step that deforms or moves the set dissipates about that
// share of its work, as the factor measured from a step would make it (viscousFactorForShare).
// A scale from the elements' size h instead would damp a smooth deformation by (L / h)^2 times
// more: on the block held by contact alone, 8.9 % of the work where F = 0.01. One factor serves
// the whole model, so it is the set's whose E / L^2 is smallest: no body is damped by more than
// that share, and a body's rigid-body motion, which has no stiffness at all, gets a tangent.
NonlinearProblem::ViscousFactor Model::viscousFactorForStiffness(double share, double dt) const {
  ViscousFactor chosen;
  for (const auto& set : elementSets_) {
    const double size = set->size(mesh_.coordinates);
    const double youngs = set->youngsModulus();
    if (!(size > 0) || !(youngs > 0)) continue;
    const double factor = share * youngs * dt / (size * size);
    if (chosen.factor > 0 && !(factor < chosen.factor)) continue;
    chosen.factor = factor;
    chosen.origin =
        fmt::format("the stiffness of '{}' (E = {:.4g}, size {:.3g})", set->name(), youngs, size);
  }
  return chosen;
}

void Model::accountEnergy(double time, const Eigen::VectorXd& displacement,
                          const Eigen::VectorXd& internalForce) {
  const int n = mesh_.numNodes();
  if (energyDisplacement_.size() != 3 * n) {
    energyDisplacement_.setZero(3 * n);
    energyForce_.setZero(3 * n);
  }
  const Eigen::VectorXd force = loadAndSupportForce(*this, time, internalForce);
  const Eigen::VectorXd increment = displacement - energyDisplacement_;
  // Forces not known (a restart from a file without them): the step's own, a one-sided rule.
  const Eigen::VectorXd& previousForce = energyForceKnown_ ? energyForce_ : force;
  energy_.externalWork += 0.5 * (force + previousForce).dot(increment);
  energy_.quadratureBound += 0.5 * std::abs((force - previousForce).dot(increment));
  RigidSurfaceWork rigid = rigidSurfaceWork(time, energyForceKnown_);
  energy_.externalWork += rigid.work;
  energy_.quadratureBound += rigid.quadratureBound;
  energyRigidForce_ = std::move(rigid.forces);

  const Eigen::Matrix3Xd current =
      mesh_.coordinates + Eigen::Map<const Eigen::Matrix3Xd>(displacement.data(), 3, n);
  energy_.strainEnergy = 0;
  for (const auto& set : elementSets_)
    energy_.strainEnergy += set->strainEnergy(mesh_.coordinates, current);
  energy_.contactEnergy = 0;
  double stepDissipation = 0;
  energy_.dissipation = 0;
  for (const auto& pair : contactPairs_) {
    energy_.contactEnergy += pair->penaltyEnergy();
    stepDissipation += pair->stepDissipation();
    energy_.dissipation += pair->dissipatedEnergy();
  }
  energyStepLength_ = time - energyTime_;
  accountViscousWork(current);
  energy_.dissipationPower = energyStepLength_ > 0 ? stepDissipation / energyStepLength_ : 0.0;
  energy_.balance = energy_.externalWork - energy_.strainEnergy - energy_.contactEnergy -
                    energy_.dissipation - energy_.stabilizationDissipation;
  energyTime_ = time;
  energyDisplacement_ = displacement;
  energyForce_ = force;
  energyForceKnown_ = true;
}

// The viscous stabilisation's work. Its force is the backward-Euler one, v_{n+1} = C m (x_{n+1} -
// x_n) / dt, booked as v_{n+1} . du. With equilibrium at both ends of the step (F - f_int = v),
// the work's trapezoidal rule then differs from the stored and dissipated energies by
// (v_{n+1} - v_n) . du / 2, which the quadrature bound adds: where the viscous forces change
// from one step to the next (a body that lands on its support), that is the balance's error.
// The stabilised thin strip's touchdown left 3.4e-7 and 4.1e-7 of its work of 1e-5 outside the
// bound before (docs/verification/energy.md). v_n . du comes from the masses' polarisation,
// (M(x_{n+1} - x_{n-1}) - M(x_n - x_{n-1}) - M(x_{n+1} - x_n)) / 2 with M(d) = sum m |d|^2.
void Model::accountViscousWork(const Eigen::Matrix3Xd& current) {
  const int n = mesh_.numNodes();
  const double rate =
      viscousFactor_ > 0 && energyStepLength_ > 0 ? viscousFactor_ / energyStepLength_ : 0.0;
  const bool earlierKnown = energyViscousRate_ > 0 && energyEarlierDisplacement_.size() == 3 * n;
  if (rate > 0 || earlierKnown) {
    const auto at = [&](const Eigen::VectorXd& displacement) -> Eigen::Matrix3Xd {
      return mesh_.coordinates + Eigen::Map<const Eigen::Matrix3Xd>(displacement.data(), 3, n);
    };
    const auto mass = [&](const Eigen::Matrix3Xd& to, const Eigen::Matrix3Xd& from) {
      double sum = 0;
      for (const auto& set : elementSets_) sum += set->viscousWork(mesh_.coordinates, to, from, 1);
      return sum;
    };
    const Eigen::Matrix3Xd previous = at(energyDisplacement_);
    const double stepMass = mass(current, previous);
    const double stepWork = rate * stepMass;
    double previousForceWork = 0;  // v_n . du
    if (earlierKnown) {
      const Eigen::Matrix3Xd earlier = at(energyEarlierDisplacement_);
      previousForceWork =
          0.5 * energyViscousRate_ * (mass(current, earlier) - mass(previous, earlier) - stepMass);
    }
    energy_.stabilizationDissipation += stepWork;
    energy_.quadratureBound += 0.5 * std::abs(stepWork - previousForceWork);
  }
  energyViscousRate_ = rate;
  if (rate > 0) {
    energyEarlierDisplacement_ = energyDisplacement_;
  } else {
    energyEarlierDisplacement_.resize(0);
  }
}

}  // namespace cc
