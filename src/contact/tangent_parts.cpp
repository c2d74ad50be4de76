// The parts of the paper's contact tangent (Tables 1 and 2), assembled from A^T u vectors.
#include "contact/tangent_parts.hpp"

#include <cmath>

namespace cc::contact {

namespace {

using Eigen::MatrixXd;

// A^T u: slave blocks N_s u, master blocks -N_m u (A maps dofs to delta r_s - delta rho).
ItemVector positionTranspose(const PointKinematics<double>& kin, const PointLayout& layout,
                             const Eigen::Vector3d& u) {
  ItemVector v = ItemVector::Zero(3 * layout.nodeCount);
  for (int a = 0; a < layout.slaveCount; ++a) {
    v.segment<3>(3 * layout.slaveLocal[a]) += layout.slaveShape[a] * u;
  }
  for (int b = 0; b < layout.masterCount; ++b) {
    // Smoothed master: the shape matrices M_k of nagata.hpp instead of N_k I.
    v.segment<3>(3 * layout.masterLocal[b]) -=
        layout.smoothMaster
            ? nagataShapeTranspose(b, kin.masterShape[b], kin.edgeBlend, layout.masterNormals, u)
            : Eigen::Vector3d(kin.masterShape[b] * u);
  }
  return v;
}

// A_j^T u: master blocks N_m,j u (A_j maps dofs to delta rho_,j); on a smoothed master
// M_k,j^T u with the blend derivatives f_e,j.
ItemVector derivativeTranspose(const shape::SurfaceShape<double>& shape, const PointLayout& layout,
                               const NagataBlend<double>& blend, int j, const Eigen::Vector3d& u) {
  ItemVector v = ItemVector::Zero(3 * layout.nodeCount);
  std::array<double, 4> weights{};
  for (int e = 0; e < 4; ++e) weights[e] = blend.first[e][j];
  for (int b = 0; b < layout.masterCount; ++b) {
    v.segment<3>(3 * layout.masterLocal[b]) +=
        layout.smoothMaster
            ? nagataShapeTranspose(b, shape.first[b][j], weights, layout.masterNormals, u)
            : Eigen::Vector3d(shape.first[b][j] * u);
  }
  return v;
}

// Relative size of h_ij (against the segment size) and Gamma^k_ij below which a master segment
// counts as flat, resp. as parametrized without connection terms.
constexpr double kFlatTolerance = 1e-12;

// K += scale (a b^T + b a^T), entry by entry: Eigen's expression built the sum in a heap
// temporary of K's size at every call.
void addSymmetricPair(MatrixXd& K, double scale, const ItemVector& a, const ItemVector& b) {
  for (Eigen::Index col = 0; col < K.cols(); ++col) {
    for (Eigen::Index row = 0; row < K.rows(); ++row) {
      K(row, col) += scale * (a[row] * b[col] + b[row] * a[col]);
    }
  }
}

}  // namespace

TangentContext makeTangentContext(const PointKinematics<double>& kin, const PointLayout& layout,
                                  const Eigen::Vector2d& xi, const Eigen::Vector3d& gapDirection) {
  const SurfaceFrame<double>& f = kin.frame;
  const shape::SurfaceShape<double> shape = shape::surfaceShape(layout.masterType, xi[0], xi[1]);
  const NagataBlend<double> blend = nagataBlend(xi[0], xi[1]);
  TangentContext c;
  c.frame = &kin.frame;
  c.weight = kin.weight;
  c.An = positionTranspose(kin, layout, f.normal);
  c.Agap = positionTranspose(kin, layout, gapDirection);
  c.fixedMasterPoint = layout.slaveCount == 0;
  for (int i = 0; i < 2; ++i) {
    c.Arho[i] = positionTranspose(kin, layout, f.rhoCov[i]);
    c.ArhoContra[i] = positionTranspose(kin, layout, f.rhoContra[i]);
    c.Ajn[i] = derivativeTranspose(shape, layout, blend, i, f.normal);
  }
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i)
      c.Ajrho[j][i] = derivativeTranspose(shape, layout, blend, j, f.rhoCov[i]);
  }
  return c;
}

// Eq. (83): eps_N (delta r_s - delta rho) . (n x m) (v_s - v), m = n except for STAS.
void normalMain(const TangentContext& c, double penaltyNormal, MatrixXd& K) {
  K.noalias() += (c.weight * penaltyNormal) * c.An * c.Agap.transpose();
}

// Eq. (83a): -eps_N g [delta rho_,j . a^ij (n x rho_i)(v_s - v) + (.) . a^ij (rho_j x n) v_,i].
void normalRotational(const TangentContext& c, double penaltyNormal, double gap, MatrixXd& K) {
  const Eigen::Matrix2d& aInv = c.frame->inverseMetric;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      // STAS (xi fixed): only N delta n, delta n = -a^ij rho_i (n . delta rho_,j); the other
      // half comes from delta xi of the projection (eq. (80)).
      const double scale = c.weight * penaltyNormal * gap * aInv(i, j);
      if (!c.fixedMasterPoint) K.noalias() -= scale * c.Ajn[j] * c.Arho[i].transpose();
      K.noalias() -= scale * c.Arho[j] * c.Ajn[i].transpose();
    }
  }
}

// Eq. (83b): -eps_N g (delta r_s - delta rho) . h^ij (rho_i x rho_j) (v_s - v).
void normalCurvature(const TangentContext& c, double penaltyNormal, double gap, MatrixXd& K) {
  const Eigen::Matrix2d& hContra = c.frame->curvatureContra;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      K.noalias() -=
          (c.weight * penaltyNormal * gap * hContra(i, j)) * c.Arho[i] * c.Arho[j].transpose();
    }
  }
}

// Eq. (100), sign changed (see header): eps_T (delta r_s - delta rho) a^ij (rho_i x rho_j)(v_s-v).
void stickMain(const TangentContext& c, double penaltyTangential, MatrixXd& K) {
  for (int i = 0; i < 2; ++i) {
    K.noalias() += (c.weight * penaltyTangential) * c.ArhoContra[i] * c.Arho[i].transpose();
  }
}

// Eqs. (100a)/(107c), sign changed: T_i [(.) a^il a^jk rho_k x rho_l v_j + delta rho_,j a^ik a^jl
// rho_k x rho_l (v_s - v)] = sum_j [A^T rho^j (A_j^T T)^T + (A_j^T T)(A^T rho^j)^T].
void tractionRotational(const TangentContext& c, const Eigen::Vector2d& traction, MatrixXd& K) {
  const Eigen::Vector2d tractionContra = c.frame->inverseMetric * traction;  // T^l = a^il T_i
  for (int j = 0; j < 2; ++j) {
    const ItemVector AjT = tractionContra[0] * c.Ajrho[j][0] + tractionContra[1] * c.Ajrho[j][1];
    if (c.fixedMasterPoint) {
      // STAS (xi fixed): only T_i delta rho^i, with delta rho^i = -(rho^i . delta rho_,k) rho^k
      // + a^ij (n . delta rho_,j) n.
      K.noalias() += c.weight * c.ArhoContra[j] * AjT.transpose();
      K.noalias() -= (c.weight * tractionContra[j]) * c.An * c.Ajn[j].transpose();
    } else {
      addSymmetricPair(K, c.weight, c.ArhoContra[j], AjT);
    }
  }
}

// Eqs. (100b)/(107d), sign changed: -T_i h^ij (.) . (rho_j x n + n x rho_j) (v_s - v).
void tractionCurvature(const TangentContext& c, const Eigen::Vector2d& traction, MatrixXd& K) {
  const Eigen::Vector2d weights = c.frame->curvatureContra * traction;  // T_i h^ij
  for (int j = 0; j < 2; ++j) addSymmetricPair(K, -c.weight * weights[j], c.Arho[j], c.An);
}

// Eqs. (107), (107a), (107b), sign changed, with the trial traction's direction e and norm:
// mu eps_N (A^T e)(A^T n)^T + eps_T mu |N| / ||T^tr|| [a^ij A^T rho_i (A^T rho_j)^T - A^T e (A^T
// e)^T]. |N| is PointResponse::compression here and in (107e): -N at a point held closed at a
// prediction, whose first term then stays the closed branch's continuation.
void slideConstitutive(const TangentContext& c, const LawParameters& law, double compression,
                       const TangentialTraction<double>& tangential, MatrixXd& K) {
  const Eigen::Vector2d direction = tangential.trialCovariant / tangential.trialNorm;
  const ItemVector Ae = direction[0] * c.ArhoContra[0] + direction[1] * c.ArhoContra[1];
  K.noalias() += (c.weight * law.friction * law.penaltyNormal) * Ae * c.Agap.transpose();
  const double scale =
      c.weight * law.penaltyTangential * law.friction * compression / tangential.trialNorm;
  for (int i = 0; i < 2; ++i) K.noalias() += scale * c.ArhoContra[i] * c.Arho[i].transpose();
  K.noalias() -= scale * Ae * Ae.transpose();
}

// Eq. (107e), sign changed: -mu |N| / ||T^tr|| (A^T e) [-e^j T_m Gamma^m_jn A^T rho^n +
// e^j T_m h_j^m A^T n]^T, with e^j = e_l a^jl and T the trial traction.
void slideUnsymmetricCurvature(const TangentContext& c, const LawParameters& law,
                               double compression, const TangentialTraction<double>& tangential,
                               MatrixXd& K) {
  const SurfaceFrame<double>& f = *c.frame;
  const Eigen::Vector2d direction = tangential.trialCovariant / tangential.trialNorm;
  const Eigen::Vector2d directionContra = f.inverseMetric * direction;
  const Eigen::Vector2d& trial = tangential.trialCovariant;
  Eigen::Vector2d christoffelWeights = Eigen::Vector2d::Zero();  // e^j T_m Gamma^m_jn
  double curvatureWeight = 0;                                    // e^j T_m h_j^m
  for (int j = 0; j < 2; ++j) {
    for (int m = 0; m < 2; ++m) {
      for (int n = 0; n < 2; ++n) {
        christoffelWeights[n] += directionContra[j] * trial[m] * f.christoffel[m](j, n);
      }
      curvatureWeight += directionContra[j] * trial[m] * f.curvatureMixed(j, m);
    }
  }
  const ItemVector Ae = direction[0] * c.ArhoContra[0] + direction[1] * c.ArhoContra[1];
  const ItemVector right = -christoffelWeights[0] * c.ArhoContra[0] -
                           christoffelWeights[1] * c.ArhoContra[1] + curvatureWeight * c.An;
  const double scale = c.weight * law.friction * compression / tangential.trialNorm;
  K.noalias() -= scale * Ae * right.transpose();
}

void paperTangent(const PointKinematics<double>& kin, const PointResponse<double>& response,
                  const PointLayout& layout, const Eigen::Vector2d& xi, const LawParameters& law,
                  const TangentParts& parts, MatrixXd& K) {
  paperTangent(kin, response, layout, xi, law, parts, kin.frame.normal, K);
}

void paperTangent(const PointKinematics<double>& kin, const PointResponse<double>& response,
                  const PointLayout& layout, const Eigen::Vector2d& xi, const LawParameters& law,
                  const TangentParts& parts, const Eigen::Vector3d& gapDirection, MatrixXd& K) {
  K.setZero(3 * layout.nodeCount, 3 * layout.nodeCount);
  if (response.state == ContactState::Open) return;
  const TangentContext c = makeTangentContext(kin, layout, xi, gapDirection);
  // Flat masters pay nothing for the curvature parts (h_ij = 0 up to round-off), and
  // parallelogram segments nothing for the Christoffel part of (107e).
  const double scale = kin.frame.metric.norm();
  const bool curved = kin.frame.curvature.norm() > kFlatTolerance * std::sqrt(scale);
  const bool connected =
      curved || kin.frame.christoffel[0].norm() + kin.frame.christoffel[1].norm() > kFlatTolerance;
  // The rotational and curvature parts carry N = eps_N g; under the augmented Lagrangian
  // N = lambda_N + eps_N g, which they take as the effective gap N / eps_N (with the plain
  // penalty N == eps_N g exactly and the gap itself is used, bit for bit as before).
  const double gap = response.normal == law.penaltyNormal * kin.gap
                         ? kin.gap
                         : response.normal / law.penaltyNormal;
  if (parts.normalMain) normalMain(c, law.penaltyNormal, K);
  if (parts.normalRotational) normalRotational(c, law.penaltyNormal, gap, K);
  if (parts.normalCurvature && curved) normalCurvature(c, law.penaltyNormal, gap, K);
  if (!response.frictional) return;
  const Eigen::Vector2d& traction = response.tangential.covariant;
  if (response.state == ContactState::Stick) {
    if (parts.stickMain) stickMain(c, law.penaltyTangential, K);
    if (parts.stickRotational) tractionRotational(c, traction, K);
    if (parts.stickCurvature && curved) tractionCurvature(c, traction, K);
    return;
  }
  if (parts.slideConstitutive)
    slideConstitutive(c, law, response.compression, response.tangential, K);
  if (parts.slideRotational) tractionRotational(c, traction, K);
  if (parts.slideCurvature && curved) tractionCurvature(c, traction, K);
  if (parts.slideUnsymmetricCurvature && connected) {
    slideUnsymmetricCurvature(c, law, response.compression, response.tangential, K);
  }
}

bool tangentSymmetric(ContactState state, const TangentParts& parts) {
  if (state != ContactState::Slip) return true;
  return !parts.slideConstitutive && !parts.slideUnsymmetricCurvature;
}

}  // namespace cc::contact
