// Closest-point projection of a slave point onto a master segment, eqs. (21)-(25): Newton's
// method on F(xi) = |r_s - rho(xi)|^2, safeguarded by step limiting and a Gauss-Newton
// fallback where F'' is not positive definite. Also the AD refinement step that makes the
// projection parameter differentiable (implicit function theorem) for the exact tangent.
#pragma once

#include <Eigen/Core>

#include "contact/geometry.hpp"

namespace cc::contact {

struct ProjectionOptions {
  int maxIterations = 30;
  double tolerance = 1e-13;   // on |delta xi| (parameter space, segment size ~2)
  double maxStep = 1.0;       // step limiting in parameter space
  double parameterBound = 3;  // iterates are kept in [-bound, bound]^2 (extrapolation allowed)
};

struct ProjectionResult {
  bool converged = false;
  // Not converged although the iterate stayed within the parameter bound: the Newton iteration
  // broke down (a non-finite step on a degenerate segment, or no convergence in maxIterations),
  // as opposed to a closest point that lies beyond the bound, i.e. off the segment.
  bool brokeDown = false;
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();
  int iterations = 0;
  // Whether xi lies in the closed segment [-1, 1]^2 (up to a small tolerance).
  bool inside(double tolerance = 1e-10) const {
    return std::abs(xi[0]) <= 1.0 + tolerance && std::abs(xi[1]) <= 1.0 + tolerance;
  }
};

// `normals`: the smoothed (Nagata) segment of nagata.hpp, else the isoparametric one.
ProjectionResult closestPointProjection(shape::SurfaceType type, const NodeMatrix<double>& nodes,
                                        const Eigen::Vector3d& point,
                                        const Eigen::Vector2d& initialGuess,
                                        const ProjectionOptions& options = {},
                                        const NodalNormals* normals = nullptr);

// One Newton step of eq. (23) taken in the scalar type Scalar at the converged parameter: the
// value is unchanged, the derivative is that of the exact projection xi(x) (implicit function).
template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> differentiableProjection(shape::SurfaceType type,
                                                     const NodeMatrix<Scalar>& nodes,
                                                     const Vec3<Scalar>& point,
                                                     const Eigen::Vector2d& converged,
                                                     const NodalNormals* normals = nullptr) {
  const Scalar xi1(converged[0]);
  const Scalar xi2(converged[1]);
  Vec3<Scalar> rho;
  std::array<Vec3<Scalar>, 2> rhoCov;
  std::array<Vec3<Scalar>, 3> rhoSecond;
  interpolateSegment(type, nodes, normals, xi1, xi2, rho, rhoCov, &rhoSecond);
  const Vec3<Scalar> distance = point - rho;
  Eigen::Matrix<Scalar, 2, 1> gradient;  // F'/(-2), eq. (24)
  Mat2<Scalar> hessian;                  // F''/2, eq. (25)
  for (int i = 0; i < 2; ++i) {
    gradient[i] = rhoCov[i].dot(distance);
    for (int j = 0; j < 2; ++j) {
      hessian(i, j) = rhoCov[i].dot(rhoCov[j]) - rhoSecond[symmetricIndex(i, j)].dot(distance);
    }
  }
  const Scalar det = hessian(0, 0) * hessian(1, 1) - hessian(0, 1) * hessian(1, 0);
  Eigen::Matrix<Scalar, 2, 1> step;
  step[0] = (hessian(1, 1) * gradient[0] - hessian(0, 1) * gradient[1]) / det;
  step[1] = (hessian(0, 0) * gradient[1] - hessian(1, 0) * gradient[0]) / det;
  return Eigen::Matrix<Scalar, 2, 1>(xi1 + step[0], xi2 + step[1]);
}

}  // namespace cc::contact
