// The contact points of a pair and how each contact kind creates them: slave nodes with their
// tributary areas (NTS), slave Gauss points (STS), master Gauss points against a rigid surface
// (STAS). A point carries its slave side, its search state, its item layout, its committed
// history and the trial state of the current iteration; ContactPair evaluates and commits them.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "contact/master_surface.hpp"
#include "contact/point_evaluation.hpp"
#include "mesh/mesh.hpp"
#include "records/result_records.hpp"

namespace cc::contact {

// The only kind-dependent decision outside the point factories and point_kinematics.hpp: NTS and
// STS points follow the master segment they project onto; an STAS point sits on a fixed master
// segment and Gauss point and meets the rigid surface along its normal line, eq. (117).
constexpr bool searchesMasterSegments(PointKind kind) {
  return kind != PointKind::SegmentToAnalytical;
}

// What the last evaluation found at a point (the trial state of the current iteration).
struct PointTrial {
  bool valid = false;
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();
  Eigen::Vector3d slavePoint = Eigen::Vector3d::Zero();
  Eigen::Vector3d masterPoint = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();           // T (Cartesian)
  Eigen::Vector2d tractionCovariant = Eigen::Vector2d::Zero();  // T_i
  double gap = 0;
  double normalTraction = 0;
  double weight = 0;
  double slipIncrement = 0;
  ContactState state = ContactState::Open;
  bool symmetric = true;
  // Lambda_T: the traction the trial started from (T^(n) carried to the current point plus
  // the augmentation), Cartesian; T - Lambda_T is the tangential multiplier update.
  Eigen::Vector3d tractionBase = Eigen::Vector3d::Zero();
};

struct PairPoint {
  // Slave side (fixed): nodes and shape values at the point; NTS area or STS Gauss point.
  int slaveCount = 0;
  std::array<int, 9> slaveNodes{};
  std::array<double, 9> slaveShape{};
  SlaveSide slave;
  int slaveFace = -1;  // STS: the slave segment (row of the slave face set)
  // STAS: the fixed master segment and Gauss point.
  int fixedSegment = -1;
  Eigen::Vector2d gaussPoint = Eigen::Vector2d::Zero();
  double gaussWeight = 0;
  // Search state of the current iteration.
  int segment = -1;
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();
  // The search state right after the last commit: a cut-back restores it, so that the retried
  // step starts its search exactly where the first attempt did.
  int committedSearchSegment = -1;
  Eigen::Vector2d committedSearchXi = Eigen::Vector2d::Zero();
  // Segment changes since the search state was last committed or restored: from the second
  // on, the point hops back and forth over an edge and the search holds it (hopped()).
  int segmentChangesInStep = 0;
  bool hopped() const { return segmentChangesInStep >= 2; }
  // The item: node list and where the slave/master/previous-master nodes sit in it.
  std::vector<int> nodes;
  PointLayout layout;
  PointHistory committed;
  PointTrial trial;
  // The evaluation pass (ContactPair::prepare counts them) that last set `trial`: a run on
  // several processes evaluates only some points per pass, and the per-pass summaries
  // (symmetry, state changes) must count only those.
  std::uint64_t evaluatedInPass = 0;
  // Augmented Lagrangian: lambda_N of the current Uzawa update and of the last commit, and
  // the tangential augmentation added to T^(n) during this step (reset at commit, when
  // T^(n+1) takes it over).
  double multiplierNormal = 0;
  double committedMultiplierNormal = 0;
  Eigen::Vector3d tractionAugmentation = Eigen::Vector3d::Zero();
};

// NTS: one point per slave node, weighted by its tributary area in the reference configuration
// (the sum over its faces of the integral of its shape function, held constant like ds in the
// paper's linearization).
std::vector<PairPoint> nodeToSegmentPoints(const Mesh& mesh, const FaceSet& slave);
// STS: integrationPoints^2 Gauss points per slave segment.
std::vector<PairPoint> segmentToSegmentPoints(const FaceSet& slave, int integrationPoints);
// One STS point of slave segment `face` at parameter xi with parametric weight `weight`: its
// slave nodes and shape values (both STS point sets are built from it).
PairPoint slaveSegmentPoint(const FaceSet& slave, int face, const Eigen::Vector2d& xi,
                            double weight);
// STS with integration=segments (segmentation.hpp, issue 16 part 1): the points of every slave
// segment on its pieces of overlap with the master segments, for the coordinates x. Built from
// x and the mesh alone, in the order of the slave faces, so every process of a run builds the
// same list. The master's search grid must be built for (nearly) x.
std::vector<PairPoint> segmentedSegmentToSegmentPoints(const FaceSet& slave,
                                                       const MasterSurface& master,
                                                       const Eigen::Matrix3Xd& x,
                                                       int integrationPoints);
// STAS: integrationPoints^2 Gauss points per master segment, each on its fixed segment.
std::vector<PairPoint> segmentToAnalyticalPoints(const FaceSet& master, int integrationPoints);

// r_s: the slave point in the coordinates x.
Eigen::Vector3d slavePosition(const PairPoint& point, const Eigen::Matrix3Xd& x);

// The trial state of a point from its evaluation.
PointTrial trialOf(const PointEvaluation& evaluation, const LawParameters& law);

// The output record of the points' last evaluated (after commit: converged) state.
ContactPairRecord pairRecord(const std::string& name, const std::vector<PairPoint>& points);
// A point's contact force on the slave side, -(N n - T) w; zero while it is open.
Eigen::Vector3d slaveSideForce(const PointTrial& trial);

}  // namespace cc::contact
