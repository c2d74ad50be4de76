// Safeguarded closest-point projection onto a master segment, eqs. (21)-(25).
#include "contact/projection.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace cc::contact {

namespace {

// Gradient g_i = rho_i . (r - rho) (= -F'/2, eq. (24)) and Hessian H_ij = a_ij - rho_ij . (r -
// rho) (= F''/2, eq. (25)) of the squared distance at xi.
void distanceDerivatives(shape::SurfaceType type, const NodeMatrix<double>& nodes,
                         const NodalNormals* normals, const Eigen::Vector3d& point,
                         const Eigen::Vector2d& xi, Eigen::Vector2d& gradient,
                         Eigen::Matrix2d& hessian, Eigen::Matrix2d& metric) {
  Eigen::Vector3d rho;
  std::array<Eigen::Vector3d, 2> rhoCov;
  std::array<Eigen::Vector3d, 3> rhoSecond;
  interpolateSegment(type, nodes, normals, xi[0], xi[1], rho, rhoCov, &rhoSecond);
  const Eigen::Vector3d distance = point - rho;
  metric = covariantMetric(rhoCov);
  for (int i = 0; i < 2; ++i) {
    gradient[i] = rhoCov[i].dot(distance);
    for (int j = 0; j < 2; ++j) {
      hessian(i, j) = metric(i, j) - rhoSecond[symmetricIndex(i, j)].dot(distance);
    }
  }
}

bool positiveDefinite(const Eigen::Matrix2d& m) {
  return m(0, 0) > 0 && m.determinant() > 0;
}

// The parameter of a closest point is known only to the round-off of the coordinates: a step
// of eps |r| along the shorter tangent vector |rho_i| is round-off, and Newton's steps stall
// there. On a thin segment far from the origin that floor lies above ProjectionOptions'
// tolerance: the Cattaneo-Mindlin cylinder deck (segments 0.094 thick, |r| = 20) stalled at steps
// of 1.0e-13 to 2.1e-13 against 1e-13, and its run stopped on "projection broke down". The
// stopping test takes this many units of that floor where it exceeds the tolerance.
constexpr double kRoundoffFloorUnits = 16;

double roundoffFloor(const Eigen::Vector3d& point, const Eigen::Matrix2d& metric) {
  const double shortestTangent = std::sqrt(metric.diagonal().minCoeff());
  return kRoundoffFloorUnits * std::numeric_limits<double>::epsilon() * point.norm() /
         shortestTangent;
}

}  // namespace

ProjectionResult closestPointProjection(shape::SurfaceType type, const NodeMatrix<double>& nodes,
                                        const Eigen::Vector3d& point,
                                        const Eigen::Vector2d& initialGuess,
                                        const ProjectionOptions& options,
                                        const NodalNormals* normals) {
  ProjectionResult result;
  Eigen::Vector2d xi = initialGuess;
  Eigen::Vector2d gradient;
  Eigen::Matrix2d hessian, metric;
  for (int iteration = 1; iteration <= options.maxIterations; ++iteration) {
    distanceDerivatives(type, nodes, normals, point, xi, gradient, hessian, metric);
    // Newton step of eq. (23); where the full Hessian is not positive definite (far from a
    // curved segment) fall back to the Gauss-Newton step with the metric alone.
    const Eigen::Matrix2d& system = positiveDefinite(hessian) ? hessian : metric;
    Eigen::Vector2d step = system.inverse() * gradient;
    if (!step.allFinite()) {
      result.brokeDown = true;
      return result;
    }
    const double length = step.norm();
    if (length > options.maxStep) step *= options.maxStep / length;
    xi = (xi + step).cwiseMax(-options.parameterBound).cwiseMin(options.parameterBound);
    result.iterations = iteration;
    if (length < std::max(options.tolerance, roundoffFloor(point, metric))) {
      result.converged = true;
      break;
    }
  }
  result.xi = xi;
  result.brokeDown =
      !result.converged && xi.cwiseAbs().maxCoeff() < options.parameterBound - options.maxStep;
  return result;
}

}  // namespace cc::contact
