// Contact law at one point, section 3.2: penalty normal traction, eqs. (62)-(63); trial
// tangential traction by parallel translation plus the penalty increment, eqs. (51), (76)-(78);
// Coulomb return mapping, eq. (79). Pure functions of gap, slip, metric and history, templated
// on the scalar type so the exact tangent can differentiate them.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "contact/geometry.hpp"
#include "records/result_records.hpp"

namespace cc::contact {

// How the trial traction carries the last converged traction into the current step. The default
// is ConvectedTranslation: the pull-back/push-forward of section 2.3.2, which keeps the traction
// attached to the material point of the master it was built on (6.1(b): 4 instead of 6 Newton
// iterations per sliding step against eq. (51) applied literally).
enum class TangentialIntegration {
  ConvectedTranslation,  // T_i^(n) convected with the master surface to the old material point,
                         // then translated in parallel to the new projection point (default)
  ParallelTranslation,   // eqs. (51), (77) literally: continuous across segment boundaries
  Convective,            // eq. (75): covariant components kept as numbers; jumps across
                         // segments with differing parametrizations (for comparison only)
};

struct LawParameters {
  double penaltyNormal = 0;      // eps_N
  double penaltyTangential = 0;  // eps_T
  double friction = 0;           // mu
  TangentialIntegration integration = TangentialIntegration::ConvectedTranslation;
};

// Eqs. (62)-(63): N = eps_N <g>, Macaulay bracket <g> = g for g <= 0, 0 otherwise. N <= 0.
template <class Scalar>
Scalar normalTraction(const Scalar& gap, double penalty) {
  return gap <= 0 ? Scalar(penalty * gap) : Scalar(0.0);
}

// Augmented Lagrangian: N = min(0, lambda_N + eps_N g) with the multiplier lambda_N <= 0 held
// fixed during a Newton solve (Uzawa); lambda_N = 0 is eq. (62). dN/dg = eps_N where active, so
// the paper's tangent parts keep their form with this N.
template <class Scalar>
Scalar augmentedNormalTraction(const Scalar& gap, double penalty, double multiplier) {
  const Scalar augmented = multiplier + penalty * gap;
  return augmented <= 0 ? augmented : Scalar(0.0);
}

template <class Scalar>
struct TangentialTraction {
  Eigen::Matrix<Scalar, 2, 1> trialCovariant;  // (T^tr)_i, eq. (77)
  Scalar trialNorm;                            // ||T^tr||, eq. (77)
  Eigen::Matrix<Scalar, 2, 1> covariant;       // T_i after the return mapping, eq. (79)
  Vec3<Scalar> vector;                         // T = T_i rho^i (Cartesian)
  ContactState state = ContactState::Stick;
};

// Eq. (51): the traction of the last converged step, a Cartesian vector in its tangent plane,
// translated in parallel to the current tangent plane, T_l^(n+1) = T^(n) . rho_l^(n+1).
template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> translateTractionInParallel(const SurfaceFrame<Scalar>& frame,
                                                        const Vec3<Scalar>& previousTraction) {
  Eigen::Matrix<Scalar, 2, 1> translated;
  for (int i = 0; i < 2; ++i) translated[i] = frame.rhoCov[i].dot(previousTraction);
  return translated;
}

// Trial step, eq. (77): the translated traction (51) plus the penalty increment
// -eps_T Delta xi^j a_ij = -eps_T (Delta rho . rho_i), eqs. (76), (78), with the slip Delta rho of
// eq. (47) (NTS/STS) or Delta rho = -u of eq. (48) (STAS).
template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> trialTraction(const SurfaceFrame<Scalar>& frame,
                                          const Vec3<Scalar>& previousTraction,
                                          const Vec3<Scalar>& slip, double penaltyTangential) {
  Eigen::Matrix<Scalar, 2, 1> trial = translateTractionInParallel(frame, previousTraction);
  for (int i = 0; i < 2; ++i) trial[i] -= penaltyTangential * slip.dot(frame.rhoCov[i]);
  return trial;
}

// Eq. (75): the naive convective update (T^tr)_i = T_i^(n) - eps_T a_ij (xi^j_(n+1) - xi^j_(n)),
// with the parameters of whatever segments the point was on.
template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> convectiveTrialTraction(const SurfaceFrame<Scalar>& frame,
                                                    const Eigen::Vector2d& previousCovariant,
                                                    const Eigen::Matrix<Scalar, 2, 1>& xi,
                                                    const Eigen::Vector2d& previousXi,
                                                    double penaltyTangential) {
  const Eigen::Matrix<Scalar, 2, 1> increment = xi - previousXi.cast<Scalar>();
  return previousCovariant.cast<Scalar>() - penaltyTangential * (frame.metric * increment);
}

// Eq. (65): ||T|| = sqrt(T_i T_j a^ij).
template <class Scalar>
Scalar tractionNorm(const Eigen::Matrix<Scalar, 2, 1>& covariant,
                    const Mat2<Scalar>& inverseMetric) {
  using std::sqrt;
  return sqrt(covariant.dot(inverseMetric * covariant));
}

// Slip, relative to the segment size, below which a trial traction counts as stick.
constexpr double kNegligibleSlip = 1e-12;
// Relative width of the band |Phi^tr| <= tol mu |N| in which a trial traction counts as lying on
// the Coulomb cone.
constexpr double kConeTolerance = 1e-9;
// At the first iterate of a step (the converged state of the last one), a point that was sliding
// keeps sliding while its trial traction lies within this fraction of mu |N| inside the cone.
// There the trial is T^(n) carried to a master that has barely moved: on the cone up to the
// change of N and of the metric since the converged state (4e-4 relative on the smoothed
// ironing die), not up to round-off. Deciding stick there gave the first Newton update the stiff
// stick tangent for half of the sliding points and 100+ stick -> slip switches in the next
// iteration (docs/verification/sliding.md). Both branches are admissible derivatives at the
// kink; from the second iterate on the decision is the exact one again, so the converged step
// is unchanged. Smoothed ironing die, developed sliding: 5.85 Newton iterations per step without
// the band, 4.52 with 1e-2, 4.35 with 0.1; the paper's decks need the same counts with each.
constexpr double kStepStartSlideBand = 0.1;

// Return mapping, eq. (79): stick if Phi^tr = ||T^tr|| - mu |N| <= 0, otherwise the trial
// traction is scaled back onto the Coulomb cone. On the cone itself (the start of a step after a
// sliding step: the translated traction has exactly the magnitude mu |N|) both branches give the
// same traction; a point that was sliding is then kept sliding, so that the first Newton
// iteration of a sliding step uses the slide tangent instead of the stiff stick one. At the
// step's first iterate (`stepStart`) the band is kStepStartSlideBand wide. `compression` is
// the normal pressure |N| (PointResponse::compression: negative only at a point held closed at
// a prediction, whose friction then points against the trial traction, continued through N = 0).
template <class Scalar>
TangentialTraction<Scalar> returnMapping(const SurfaceFrame<Scalar>& frame,
                                         const Eigen::Matrix<Scalar, 2, 1>& trial,
                                         const Scalar& compression, double friction,
                                         double penaltyTangential, bool wasSliding,
                                         bool stepStart = false) {
  using std::abs;
  using std::sqrt;
  TangentialTraction<Scalar> result;
  result.trialCovariant = trial;
  result.trialNorm = tractionNorm(trial, frame.inverseMetric);
  const Scalar limit = friction * compression;
  // A trial traction from a slip at round-off level of the coordinates is no slip: without this
  // tolerance a point touching with N = 0 (g = 0 at the start) would slide on noise in a random
  // direction and carry no tangential stiffness into the first Newton iteration.
  const double slack = penaltyTangential * kNegligibleSlip * sqrt(scalarValue(frame.metric(0, 0))) +
                       kConeTolerance * scalarValue(limit);
  const double excess = scalarValue(result.trialNorm) - scalarValue(limit);
  const double keepSliding = slack + (stepStart ? kStepStartSlideBand * scalarValue(limit) : 0.0);
  // No slip direction without a trial traction (T^tr = 0 with a bound of zero or below).
  const bool slides =
      scalarValue(result.trialNorm) > 0 &&
      (excess > slack || (wasSliding && excess >= -keepSliding && scalarValue(limit) > 0));
  if (!slides) {
    result.state = ContactState::Stick;
    result.covariant = trial;
  } else {
    result.state = ContactState::Slip;
    result.covariant = trial * (limit / result.trialNorm);
  }
  result.vector =
      result.covariant[0] * frame.rhoContra[0] + result.covariant[1] * frame.rhoContra[1];
  return result;
}

}  // namespace cc::contact
