// One contact point: its kinematics (master frame, slave point, gap, slip, integration weight),
// its response under the contact law, and its force on the item's nodes from the weak form
// eq. (60): delta W_c = (N delta g + T_j delta xi^j) ds with delta g and delta xi^j of eqs.
// (58), (61). All templated on the scalar type: double for the residual, an AD scalar for the
// exact tangent. The contact kinds (NTS, STS, STAS) differ only in how they fill the kinematics.
//
// Sign convention (DESIGN.md): g = (r_s - rho) . n <= 0 in contact, N = eps_N <g> <= 0. T is the
// tangential traction acting on the slave (opposing its slip, eq. (66)). The force added to the
// global internal-force vector is A^T (N n - T) w, where A maps the item's dofs to
// delta r_s - delta rho (slave block N_s, master block -N_m(xi)), so that both penalty springs
// have positive stiffness.
#pragma once

#include <Eigen/Core>
#include <array>
#include <limits>

#include "contact/friction_law.hpp"
#include "contact/geometry.hpp"

namespace cc::contact {

// Beyond a free edge of the master surface (an edge without a neighbour) a projection still
// counts with the full contact force up to kFreeEdgeTolerance in parameter space (1% of the half
// segment): a slave node lying on the master's boundary edge, common where both bodies end in the
// same plane, must not drop out of contact whenever it moves by round-off or by a Poisson
// contraction across the edge. Beyond that, with `edge=fade`, the force falls to zero smoothly
// over kFreeEdgeBand (freeEdgeFactor); by default (`edge=sharp`, as the paper's examples ran)
// it jumps to zero. With a force that jumped to zero at the tolerance, a slave node on the free
// edge of a die as wide as the slab had no equilibrium: held in contact it was pushed out, let
// go it came back, and Newton cycled with period 2-3 through every cut-back (issue 14,
// ironing_nts_mu03_equal). The band is 10% of the segment; the force carried beyond the edge is
// the regularization's error.
constexpr double kFreeEdgeTolerance = 1e-2;
constexpr double kFreeEdgeBand = 0.2;

// An item has at most 27 nodes (9 slave, 9 master, 9 of the previous master segment: the arrays
// of PointLayout), so vectors over its dofs fit a capacity of 81 on the stack. Heap vectors
// (Eigen::VectorXd) in the tangents allocated in every operation (issue 13: ~7 % of the samples
// of a die-dragging run in the exact tangent).
inline constexpr int kMaxItemNodes = 27;
inline constexpr int kMaxItemDofs = 3 * kMaxItemNodes;
using ItemVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxItemDofs, 1>;

// Where the nodes of one contact item sit in its node list (local indices), and the slave
// side's fixed shape-function values at the slave point.
struct PointLayout {
  shape::SurfaceType masterType = shape::SurfaceType::Quad4;
  int masterCount = 0;
  std::array<int, 9> masterLocal{};
  int slaveCount = 0;  // NTS: 1, STS: 4 or 9, STAS: 0 (rigid slave)
  std::array<int, 9> slaveLocal{};
  std::array<double, 9> slaveShape{};
  int previousMasterCount = 0;  // nodes of the segment of the last converged projection, when
  std::array<int, 9> previousMasterLocal{};  // it differs from the current one (eq. (47))
  shape::SurfaceType previousMasterType = shape::SurfaceType::Quad4;
  int nodeCount = 0;  // size of the item's node list
  // Edges of the current master segment without a neighbour (bit e for edge e, numbered as in
  // master_surface.cpp: xi2 = -1, xi1 = 1, xi2 = 1, xi1 = -1).
  unsigned freeEdges = 0;
  // Smoothed master (nagata.hpp, Quad4): the nodal normals of the current and the previous
  // segment, held fixed over the step; the geometry (and the tangent) is that of the Nagata
  // patch for these normals.
  bool smoothMaster = false;
  NodalNormals masterNormals{};
  NodalNormals previousMasterNormals{};
  const NodalNormals* currentNormals() const { return smoothMaster ? &masterNormals : nullptr; }
  const NodalNormals* previousNormals() const {
    if (!smoothMaster) return nullptr;
    return previousMasterCount == 0 ? &masterNormals : &previousMasterNormals;
  }
};
// kMaxItemNodes is what PointLayout can hold: slave, master and previous master nodes.
static_assert(kMaxItemNodes == 3 * std::tuple_size_v<decltype(PointLayout::slaveLocal)> &&
              kMaxItemNodes == 3 * std::tuple_size_v<decltype(PointLayout::masterLocal)>);

// The gap recorded for a converged step at which the point had no projection: as if far open
// (finite, so that the restart data stay finite).
inline constexpr double kNoGap = std::numeric_limits<double>::max();

// History of a contact point, committed only when a step converges (DESIGN.md).
struct PointHistory {
  bool projected = false;  // a projection existed at the last converged step
  int segment = -1;        // master segment of that projection (NTS/STS)
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();           // T^(n), Cartesian, eq. (49)
  Eigen::Vector2d tractionCovariant = Eigen::Vector2d::Zero();  // T_i^(n) (convective update)
  Eigen::Vector3d masterPoint = Eigen::Vector3d::Zero();        // STAS: rho at step n
  Eigen::Vector3d surfaceOffset = Eigen::Vector3d::Zero();      // STAS: rigid translation at step n
  ContactState state = ContactState::Open;
  double accumulatedSlip = 0;
  // Augmented Lagrangian (contact_pair_augmentation.cpp): the normal multiplier lambda_N <= 0
  // of the current Uzawa update, and the tangential augmentation A of this step, a Cartesian
  // vector added to the trial traction by eq. (51) (zero for the paper's penalty).
  double multiplierNormal = 0;
  Eigen::Vector3d tractionAugmentation = Eigen::Vector3d::Zero();
  // The gaps of the last two converged steps, g_n and g_(n-1) (kNoGap where the point had no
  // projection): the gap history that predicts the point's contact state at an extrapolated
  // first iterate (ContactPair::holdsClosedAtPrediction).
  double gap = kNoGap;
  double previousGap = kNoGap;
  // Set per evaluation, not committed: this is the step's first iterate (the first evaluation
  // after a commit or a restore), where returnMapping keeps sliding points sliding in a band.
  bool stepStart = false;
  // Set per evaluation, not committed: at this (extrapolated, first) iterate the point keeps
  // the penalty branch N = eps_N g also where g > 0.
  bool heldClosed = false;
};

template <class Scalar>
struct PointKinematics {
  SurfaceFrame<Scalar> frame;           // master frame at the contact point
  Eigen::Matrix<Scalar, 2, 1> xi;       // its parameter on the master segment
  std::array<Scalar, 9> masterShape{};  // N_m(xi) (xi may depend on the nodes)
  std::array<Scalar, 4> edgeBlend{};    // smoothed master: f_e(xi) of nagata.hpp
  Vec3<Scalar> slavePoint;              // r_s
  Scalar gap;                           // g, eq. (27) (STAS: xi^3 of eq. (117))
  Vec3<Scalar> slip;                    // Delta rho, eq. (47) or -u of eq. (48)
  Vec3<Scalar> convectedTraction;       // T^(n) carried with the master surface (see
                                        // TangentialIntegration::ConvectedTranslation)
  Scalar weight;                        // ds times the quadrature weight
};

template <class Scalar>
struct PointResponse {
  Scalar normal = Scalar(0.0);  // N
  // The pressure that bounds friction, mu * compression: |N|, or -N continued through g = 0 for
  // a point held closed at a prediction (negative where the prediction opens it).
  Scalar compression = Scalar(0.0);
  TangentialTraction<Scalar> tangential;
  ContactState state = ContactState::Open;
  bool frictional = false;
};

// The share of the contact force a point keeps beyond the master's free edges: 1 up to
// kFreeEdgeTolerance, then 1 - 3 s^2 + 2 s^3 with s the further excess over kFreeEdgeBand, 0
// beyond (C1 in xi, so the force goes to zero without a jump or a kink; see kFreeEdgeTolerance).
template <class Scalar>
Scalar freeEdgeFactor(const Eigen::Matrix<Scalar, 2, 1>& xi, unsigned freeEdges) {
  Scalar factor(1.0);
  for (int edge = 0; edge < 4; ++edge) {
    if (!(freeEdges & (1u << edge))) continue;
    const Scalar excess = edge == 0   ? Scalar(-1.0 - xi[1])
                          : edge == 1 ? Scalar(xi[0] - 1.0)
                          : edge == 2 ? Scalar(xi[1] - 1.0)
                                      : Scalar(-1.0 - xi[0]);
    const Scalar s = (excess - kFreeEdgeTolerance) / kFreeEdgeBand;
    if (scalarValue(s) >= 1) return Scalar(0.0);
    if (scalarValue(s) > 0) factor *= 1.0 - s * s * (3.0 - 2.0 * s);
  }
  return factor;
}

// Normal penalty, trial step and return mapping at one point, Table 1 / Table 2.
template <class Scalar>
PointResponse<Scalar> pointResponse(const PointKinematics<Scalar>& kin, const PointHistory& history,
                                    const LawParameters& law) {
  PointResponse<Scalar> response;
  if (history.multiplierNormal == 0) {
    // Open: g > 0, no traction (Table 1, loop 3); a held point keeps N = eps_N g there, a small
    // tension for one iterate (ContactPair::holdsClosedAtPrediction).
    if (kin.gap > 0 && !history.heldClosed) return response;
    response.normal = history.heldClosed ? Scalar(law.penaltyNormal * kin.gap)
                                         : normalTraction(kin.gap, law.penaltyNormal);
  } else {  // augmented Lagrangian: open where lambda_N + eps_N g > 0
    response.normal = augmentedNormalTraction(kin.gap, law.penaltyNormal, history.multiplierNormal);
    if (response.normal == 0) return response;
  }
  // A held point continues the closed branch linearly, its friction bound too: mu |N| would
  // grow as the prediction opens the point, so that the first update, linearized there, pushed
  // its friction the wrong way (the stiff ball with NTS, mu = 0.3: the first update 5 times the
  // step's whole correction, one iteration more per step than at mu = 0).
  using std::abs;
  response.compression =
      history.heldClosed ? Scalar(-response.normal) : Scalar(abs(response.normal));
  response.state = ContactState::Stick;
  response.tangential.covariant.setZero();
  response.tangential.trialCovariant.setZero();
  response.tangential.trialNorm = Scalar(0.0);
  response.tangential.vector.setZero();
  // Friction needs the projection of the last converged step (eq. (47)/(48)); a point that had
  // none (it came onto the master surface during this step) carries only normal traction in
  // this step, consistently in residual and tangent.
  if (law.friction > 0 && history.projected) {
    response.frictional = true;
    // Zero only to quiet GCC's maybe-uninitialized: the switch covers every integration.
    Eigen::Matrix<Scalar, 2, 1> trial = Eigen::Matrix<Scalar, 2, 1>::Zero();
    switch (law.integration) {
      case TangentialIntegration::ParallelTranslation:
        trial = trialTraction(kin.frame, Vec3<Scalar>(history.traction.cast<Scalar>()), kin.slip,
                              law.penaltyTangential);
        break;
      case TangentialIntegration::ConvectedTranslation:
        trial = trialTraction(kin.frame, kin.convectedTraction, kin.slip, law.penaltyTangential);
        break;
      case TangentialIntegration::Convective:
        trial = convectiveTrialTraction(kin.frame, history.tractionCovariant, kin.xi, history.xi,
                                        law.penaltyTangential);
        break;
    }
    if (!history.tractionAugmentation.isZero(0)) {
      trial += translateTractionInParallel(
          kin.frame, Vec3<Scalar>(history.tractionAugmentation.cast<Scalar>()));
    }
    response.tangential =
        returnMapping(kin.frame, trial, response.compression, law.friction, law.penaltyTangential,
                      history.state == ContactState::Slip, history.stepStart);
    response.state = response.tangential.state;
  }
  return response;
}

// Force on the item's dofs, A^T (N n - T) w (node-major, 3 per local node).
template <class Scalar>
void pointForce(const PointKinematics<Scalar>& kin, const PointResponse<Scalar>& response,
                const PointLayout& layout, Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& force) {
  force.setZero(3 * layout.nodeCount);
  if (response.state == ContactState::Open) return;
  const Vec3<Scalar> traction =
      (response.normal * kin.frame.normal - response.tangential.vector) * kin.weight;
  for (int a = 0; a < layout.slaveCount; ++a) {
    force.template segment<3>(3 * layout.slaveLocal[a]) += layout.slaveShape[a] * traction;
  }
  for (int b = 0; b < layout.masterCount; ++b) {
    // Smoothed master: rho = sum_k M_k x_k with 3x3 shape matrices M_k (nagata.hpp), so the
    // master share of the point force is M_k^T traction.
    force.template segment<3>(3 * layout.masterLocal[b]) -=
        layout.smoothMaster ? nagataShapeTranspose(b, kin.masterShape[b], kin.edgeBlend,
                                                   layout.masterNormals, traction)
                            : Vec3<Scalar>(kin.masterShape[b] * traction);
  }
}

}  // namespace cc::contact
