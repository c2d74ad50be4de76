// The parts of the paper's contact tangent, Tables 1 and 2, each its own small function:
// normal main (83), rotational (83a), curvature (83b); stick main (100), rotational (100a),
// curvature (100b); slide constitutive (107, 107a, 107b), rotational (107c), curvature (107d),
// unsymmetric curvature (107e). A per-pair TangentParts flag set selects which are assembled.
//
// Every part is a bilinear form in (delta r_s - delta rho) = A delta x, delta rho_,j = A_j
// delta x and the same for the increment, so it is assembled from the vectors A^T u and A_j^T u
// (u = n, rho_i, rho^i) of TangentContext. The paper writes D(delta W_c) with N <= 0 in the
// normal part and T as the traction on the slave in the tangential parts; with our residual
// A^T (N n - T) w the normal parts keep the paper's sign and the tangential parts change it.
#pragma once

#include <Eigen/Core>

#include "contact/contact_point.hpp"

namespace cc::contact {

// Paper: the parts of Tables 1-2 selected by TangentParts. Exact: the linearization of the
// discrete algorithm itself (automatic differentiation, contact/exact_tangent.hpp).
enum class TangentMode { Paper, Exact };

// Which parts of the paper's tangent (Tables 1 and 2) are assembled. The residual never depends
// on these flags. The model builder fills it from the deck's TangentPartsSpec.
struct TangentParts {
  bool normalMain = true;                 // eq. (83)
  bool normalRotational = true;           // eq. (83a)
  bool normalCurvature = true;            // eq. (83b)
  bool stickMain = true;                  // eq. (100)
  bool stickRotational = true;            // eq. (100a)
  bool stickCurvature = true;             // eq. (100b)
  bool slideConstitutive = true;          // eqs. (107), (107a), (107b)
  bool slideRotational = true;            // eq. (107c)
  bool slideCurvature = true;             // eq. (107d)
  bool slideUnsymmetricCurvature = true;  // eq. (107e)
};

struct TangentContext {
  const SurfaceFrame<double>* frame = nullptr;
  double weight = 0;
  ItemVector An;                                   // A^T n
  ItemVector Agap;                                 // A^T m, delta g = (A delta x) . m
  bool fixedMasterPoint = false;                   // STAS: xi fixed, delta xi = 0
  std::array<ItemVector, 2> Arho;                  // A^T rho_i
  std::array<ItemVector, 2> ArhoContra;            // A^T rho^i
  std::array<ItemVector, 2> Ajn;                   // A_j^T n
  std::array<std::array<ItemVector, 2>, 2> Ajrho;  // [j][i] = A_j^T rho_i
};

// gapDirection m: delta g = (delta r_s - delta rho) . m in the main parts. NTS and STS: m = n
// (the slave point is material, eq. (80)). STAS: the rigid surface point slides along the
// surface as the master point moves, and eq. (117) linearized gives m = nu / (n . nu) with nu the
// rigid surface's normal there (m = n when the master segment is parallel to the surface).
TangentContext makeTangentContext(const PointKinematics<double>& kin, const PointLayout& layout,
                                  const Eigen::Vector2d& xi, const Eigen::Vector3d& gapDirection);

void normalMain(const TangentContext& c, double penaltyNormal, Eigen::MatrixXd& K);
void normalRotational(const TangentContext& c, double penaltyNormal, double gap,
                      Eigen::MatrixXd& K);
void normalCurvature(const TangentContext& c, double penaltyNormal, double gap, Eigen::MatrixXd& K);
void stickMain(const TangentContext& c, double penaltyTangential, Eigen::MatrixXd& K);
// Rotational and curvature parts of delta xi^i's linearization, eq. (98)-(98a), weighted by the
// traction T_i: eqs. (100a)/(100b) with the stick traction, (107c)/(107d) with the slide one.
void tractionRotational(const TangentContext& c, const Eigen::Vector2d& traction,
                        Eigen::MatrixXd& K);
void tractionCurvature(const TangentContext& c, const Eigen::Vector2d& traction,
                       Eigen::MatrixXd& K);
void slideConstitutive(const TangentContext& c, const LawParameters& law, double normal,
                       const TangentialTraction<double>& tangential, Eigen::MatrixXd& K);
void slideUnsymmetricCurvature(const TangentContext& c, const LawParameters& law, double normal,
                               const TangentialTraction<double>& tangential, Eigen::MatrixXd& K);

// The paper's tangent of one point with the selected parts; K is sized and zeroed here.
void paperTangent(const PointKinematics<double>& kin, const PointResponse<double>& response,
                  const PointLayout& layout, const Eigen::Vector2d& xi, const LawParameters& law,
                  const TangentParts& parts, Eigen::MatrixXd& K);
// The same with the gap direction m of makeTangentContext (STAS).
void paperTangent(const PointKinematics<double>& kin, const PointResponse<double>& response,
                  const PointLayout& layout, const Eigen::Vector2d& xi, const LawParameters& law,
                  const TangentParts& parts, const Eigen::Vector3d& gapDirection,
                  Eigen::MatrixXd& K);

// Whether the selected parts give a symmetric matrix in this state (slide (107) and (107e) do
// not; everything else does).
bool tangentSymmetric(ContactState state, const TangentParts& parts);

}  // namespace cc::contact
