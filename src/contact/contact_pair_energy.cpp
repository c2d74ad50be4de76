// Energy of a contact pair (issue 16, part 4): the stored energy of the penalty springs and the
// frictional dissipation. With the penalty regularization of section 3.2 the normal traction is
// N = eps_N g (eq. (62)) and the tangential traction is eps_T times the elastic part of the slip
// (eqs. (76)-(79)), so the springs store w (N^2 / (2 eps_N) + |T|^2 / (2 eps_T)) per point, and
// the return mapping's slip Delta lambda = (||T^tr|| - mu |N|) / eps_T dissipates
// w mu |N| Delta lambda = w |T| Delta lambda (backward Euler: the traction at the end of the
// step times the slip of the step).
#include <cmath>

#include "contact/contact_pair.hpp"

namespace cc::contact {

double ContactPair::penaltyEnergy() const {
  const LawParameters& law = config_.law;
  double energy = 0;
  for (const PairPoint& point : points_) {
    const PointTrial& t = point.trial;
    if (!t.valid || t.state == ContactState::Open) continue;
    double density = 0;
    if (law.penaltyNormal > 0)
      density += 0.5 * t.normalTraction * t.normalTraction / law.penaltyNormal;
    if (law.penaltyTangential > 0)
      density += 0.5 * t.traction.squaredNorm() / law.penaltyTangential;
    energy += t.weight * density;
  }
  return energy;
}

Eigen::Vector3d ContactPair::slaveSideForce() const {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (const PairPoint& point : points_) {
    if (point.trial.valid) force += contact::slaveSideForce(point.trial);
  }
  return force;
}

double ContactPair::pointDissipation(const PointTrial& t) const {
  if (!t.valid || t.state != ContactState::Slip) return 0;
  return t.weight * config_.law.friction * std::abs(t.normalTraction) * t.slipIncrement;
}

void ContactPair::accountDissipation() {
  stepDissipation_ = 0;
  for (const PairPoint& point : points_) stepDissipation_ += pointDissipation(point.trial);
  dissipatedEnergy_ += stepDissipation_;
}

}  // namespace cc::contact
