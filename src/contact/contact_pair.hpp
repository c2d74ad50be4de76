// A contact pair as a Contribution to the global system: evaluates its contact points (made by
// contact_points.hpp for each kind) on the master segments the search tracking
// (segment_tracking.hpp) assigns them, and commits the point history (xi, rho, T, state,
// accumulated slip) only when a step converges; a cut-back restores it.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "contact/anderson_acceleration.hpp"
#include "contact/contact_points.hpp"
#include "contact/point_evaluation.hpp"
#include "contact/segment_tracking.hpp"
#include "fem/contribution.hpp"
#include "mesh/mesh.hpp"
#include "records/result_records.hpp"

namespace cc::contact {

struct ContactPairConfig {
  std::string name;
  PointKind kind = PointKind::NodeToSegment;
  LawParameters law;
  int integrationPoints = 2;  // Gauss points per direction (STS, STAS)
  TangentMode tangentMode = TangentMode::Paper;
  TangentParts parts;
  bool automaticPenalty = false;  // eps_N/eps_T chosen by the model builder (printed, stored)
  // Augmented Lagrangian (contact_pair_augmentation.cpp): Uzawa updates per step until the
  // multiplier updates, integrated over the surface, are below augmentationTolerance times the
  // normal contact force.
  bool augmented = false;
  double augmentationTolerance = 1e-3;
  int maxAugmentations = 100;
  int accelerationDepth = 5;  // Anderson depth of the Uzawa updates (0: plain Uzawa)
  // When the updates stall at a penalty below referencePenalty, raise the penalties
  // (contact_pair_augmentation.cpp, kStallWindow).
  bool growPenalty = true;
  // The automatic penalty at eps_scale = 1 (model/automatic_penalty.hpp), also when the deck
  // gives eps: a penalty below it tightens the stopping rule so that the penetration left is
  // bounded as with this one (0: unknown, the rule uses eps itself).
  double referencePenalty = 0;
  // The mean depth of the element layer behind the softer surface (the one of lower E/h,
  // model/automatic_penalty.hpp; 0: unknown): the scale the deepest penetration is measured
  // against (ContactPair::penetrationWarning).
  double layerDepth = 0;
  // Smoothed master (issue 16, part 2; NTS/STS with Quad4 masters): search, projection, gap,
  // normal and curvature on Nagata patches (nagata.hpp) over nodal normals taken from the
  // converged configuration at the start of each step and held fixed over it.
  bool smoothMaster = false;
  // Smoothed master: edges where the facets turn by more than this (radians) stay sharp.
  double creaseAngle = kDefaultCreaseAngle;
  // Free master edges where the force fades out (contact_point.hpp, kFreeEdgeBand).
  bool fadingEdges = false;
  // Segment-exact STS integration (issue 16, part 1; segmentation.hpp): the points of each
  // slave segment are placed on its pieces of overlap with the master segments, rebuilt from
  // the converged configuration at the start of every step and fixed over the step
  // (contact_pair_segments.cpp). False: integrationPoints^2 Gauss points, as in the paper.
  bool segmentIntegration = false;
};

// A rigid translation of the STAS surface as a function of time (called serially).
using SurfaceMotion = std::function<Eigen::Vector3d(double time)>;

class ContactPair : public Contribution {
 public:
  static std::unique_ptr<ContactPair> nodeToSegment(ContactPairConfig config, const Mesh& mesh,
                                                    const FaceSet& master, const FaceSet& slave);
  static std::unique_ptr<ContactPair> segmentToSegment(ContactPairConfig config,
                                                       const FaceSet& master, const FaceSet& slave);
  static std::unique_ptr<ContactPair> segmentToAnalytical(ContactPairConfig config,
                                                          const FaceSet& master,
                                                          RigidSurface surface,
                                                          SurfaceMotion motion);

  std::string name() const override { return config_.name; }
  // STAS: the rigid surface's translation at `time` (a drive of the model,
  // NonlinearProblem::rigidSurfaceOffsets); empty for a pair without a moving rigid surface.
  std::optional<Eigen::Vector3d> surfaceOffsetAt(double time) const {
    if (!motion_) return std::nullopt;
    return motion_(time);
  }
  LocalStatus prepare(const AssemblyState& state) override;
  std::size_t itemCount() const override { return points_.size(); }
  std::span<const int> itemNodes(std::size_t item) const override { return points_[item].nodes; }
  std::uint64_t topologyVersion() const override { return topologyVersion_; }
  // A node of the master segment point `item` projects onto now; -1 when it has none (open
  // search, rigid master). Runs on several processes count the points whose master segment
  // moved to another process (model_distribution.cpp).
  int masterNodeOf(std::size_t item) const {
    const PairPoint& point = points_[item];
    return point.segment >= 0 && point.layout.masterCount > 0
               ? point.nodes[static_cast<std::size_t>(point.layout.masterLocal[0])]
               : -1;
  }
  LocalStatus evaluate(std::size_t item, const AssemblyState& state, Eigen::VectorXd& force,
                       Eigen::MatrixXd* tangent) override;
  bool tangentSymmetric() const override;
  void commitStep() override;
  void restoreStep() override;
  // Each point's master segment, parameter and segment changes in the step: remembered at a
  // Newton iterate, recalled before a trial evaluation off it (solver/nonlinear_problem.hpp).
  void rememberSearch();
  void recallSearch();

  // Points whose trial state or master segment changed since the last call, and the points in
  // contact (contact_pair_diagnostics.cpp; Newton logs it per iteration). Only the points
  // evaluated since the last prepare() count (all of them in a serial run).
  ContactChanges takeChanges();
  // The points in contact on another master segment than at the last takeChanges(), not
  // counted as changes: the master edges a trial evaluation off an iterate (the line search's)
  // crossed. Only the points evaluated since the last prepare() count.
  PendingCrossings pendingCrossings() const;
  // How often each point changed its state (open/stick/slip) and, in contact, its master
  // segment in the calls of takeChanges() since the last commit or restore: the points a
  // stalled Newton solve keeps switching (issue 14), which its failure message names. Only the
  // points this process evaluates count; empty before the first call.
  const std::vector<int>& stateChangesInAttempt() const { return stateChangesInAttempt_; }
  const std::vector<int>& segmentChangesInAttempt() const { return segmentChangesInAttempt_; }
  // The mesh node a message names point `item` by: the slave node with the largest shape value
  // at it (NTS: its own node), for STAS the first node of its slab face.
  int nearestNode(std::size_t item) const;

  // Output of the last evaluated (after commit: converged) state.
  ContactPairRecord record() const;

  // The deepest penetration -g of a point in contact over the converged steps so far, and the
  // time of the step it was reached in (contact_pair_diagnostics.cpp).
  double deepestPenetration() const { return deepestPenetration_; }
  double deepestPenetrationTime() const { return deepestPenetrationTime_; }
  // A line for the end of a run when that penetration exceeded kPenetrationWarningShare of
  // ContactPairConfig::layerDepth ("" otherwise, or when the depth is unknown).
  std::string penetrationWarning() const;

  // Augmented Lagrangian (contact_pair_augmentation.cpp): after a converged Newton solve, checks
  // the stopping rule and otherwise updates the multipliers (Uzawa) for another solve.
  enum class Augmentation { Converged, Updated, Failed };
  Augmentation augment();
  const std::string& augmentationMessage() const { return lastAugmentationMessage_; }
  // What the last augment() changed beyond the multipliers (a raised penalty), once; or empty.
  std::string takeAugmentationNote() { return std::exchange(augmentationNote_, {}); }
  int augmentations() const { return augmentations_; }

  // Penalty continuation (solver/load_stepper.cpp): the larger of the pair's penalties over its
  // automatic penalty (0: unknown), and a factor on the penalties it was built with, for the
  // solves of a step that approach a stiff penalty from the automatic one (1 restores them;
  // a factor is never applied below the automatic penalty, nor to a pair whose is unknown).
  double penaltyRatio() const;
  void scalePenalties(double factor);

  // Energy (contact_pair_energy.cpp): the stored penalty energy of the last evaluated state, and
  // the frictional dissipation of the last committed step and since the start of the run.
  double penaltyEnergy() const;
  // The contact force on the pair's slave side in the last evaluated state, sum of -(N n - T) w
  // over its closed points (the results' total_force). In STAS the slave is the rigid surface:
  // minus this force is what the surface exerts on the body, whose work the energy account
  // books.
  Eigen::Vector3d slaveSideForce() const;
  double stepDissipation() const { return stepDissipation_; }
  double dissipatedEnergy() const { return dissipatedEnergy_; }
  // A run continued from a restart goes on from the dissipation stored there.
  void restoreDissipatedEnergy(double energy) { dissipatedEnergy_ = energy; }

  // Restart (contact_pair_history.cpp): the committed history of every point and the search
  // state it continues from, one column of kHistoryRows numbers per point, and its
  // restoration. importHistory throws std::invalid_argument if the table does not fit the pair.
  static constexpr int kHistoryRows = 29;
  Eigen::MatrixXd exportHistory() const;
  void importHistory(const Eigen::MatrixXd& table);
  const ContactPairConfig& config() const { return config_; }
  int pointCount() const { return static_cast<int>(points_.size()); }

  // Smoothed master: its creases, from the mesh as given (MasterSurface::findCreases), and how
  // many shared edges are creases.
  void findCreases(const Eigen::Matrix3Xd& reference) { tracker_.findCreases(reference); }
  int creaseCount() const { return tracker_.master().creaseCount(); }
  MasterSurface::FacetTurns facetTurns(const Eigen::Matrix3Xd& reference) const {
    return tracker_.master().facetTurns(reference);
  }

 private:
  ContactPair(ContactPairConfig config, const FaceSet& master, std::vector<PairPoint> points);
  const MasterSurface& master() const { return tracker_.master(); }
  void buildItem(PairPoint& point) const;
  void forgetChangesInAttempt();  // contact_pair_diagnostics.cpp
  // The parts of importHistory (contact_pair_history.cpp).
  struct HistoryLayout {
    bool legacy = false;           // written before the augmentation rows
    bool withGaps = false;         // holds the gap history
    bool withPenetration = false;  // holds the penetration watch
  };
  HistoryLayout historyLayout(const Eigen::MatrixXd& table) const;
  void importPointHistory(int i, const Eigen::Ref<const Eigen::VectorXd>& column, bool withGaps);
  void importAugmentation(const Eigen::MatrixXd& table);
  void importDeepestPenetration(const Eigen::MatrixXd& table);
  // The search tracking of NTS/STS points; rebuilds the items of the points that moved.
  LocalStatus searchSegments(const Eigen::Matrix3Xd& x, double time);
  // Table 1, step 1: the projections in the initial configuration start the history.
  void initializeHistory(const AssemblyState& state);
  PointSetup setupFor(const PairPoint& point) const;
  // STAS at the step's first iterate: the rigid surface's motion over the step enters linearly
  // (contact_pair.cpp), unless Newton's predictor has already moved the bodies with it.
  bool predictsSurfaceMotion(const PointSetup& setup, const AssemblyState& state) const;
  LocalStatus evaluateExactly(PairPoint& point, const PointSetup& setup,
                              const NodeMatrix<double>& nodes, Eigen::VectorXd& force,
                              Eigen::MatrixXd* tangent);
  LocalStatus evaluateSurfaceMotionPredictor(PairPoint& point, const PointSetup& setup,
                                             const AssemblyState& state,
                                             const NodeMatrix<double>& nodes,
                                             Eigen::VectorXd& force, Eigen::MatrixXd* tangent);
  // Dissipation w mu |N| Delta lambda of a point's trial state (contact_pair_energy.cpp).
  double pointDissipation(const PointTrial& trial) const;
  void accountDissipation();  // at commit: adds the step's dissipation to the run's
  // At commit / cut-back: the multipliers of the step become committed / are forgotten.
  void commitAugmentation();
  void restoreAugmentation();
  // aug_grow: raises the penalties when the updates (ratio: this one over the normal force)
  // stall below the automatic penalty; true if it did.
  bool raisePenaltyIfStalled(double ratio);
  // augment()'s parts: the weighted multiplier update against the normal contact force, and the
  // Uzawa image of the multipliers combined by Anderson acceleration.
  struct AugmentationMeasure {
    double force = 0;   // sum w |N|
    double update = 0;  // sum of the weighted multiplier updates
  };
  AugmentationMeasure measureAugmentation() const;
  void updateMultipliers();
  // integration=segments (contact_pair_segments.cpp): the points of the segmentation at the
  // converged configuration of the step's start, each with the history of the nearest old point
  // on its slave segment, re-projected there.
  LocalStatus resegment(const AssemblyState& state);
  void inheritHistory(PairPoint& point, const Eigen::Matrix3Xd& x) const;

  ContactPairConfig config_;
  double builtPenaltyNormal_ = 0, builtPenaltyTangential_ = 0;  // before scalePenalties
  SegmentTracker tracker_;
  std::vector<PairPoint> points_;
  // What takeChanges() saw last, per point.
  std::vector<ContactState> countedState_;
  std::vector<int> countedSegment_;
  std::vector<int> stateChangesInAttempt_, segmentChangesInAttempt_;
  std::vector<int> moved_;  // scratch of searchSegments
  struct SearchPosition {
    int segment;
    Eigen::Vector2d xi;
    int segmentChangesInStep;
  };
  std::vector<SearchPosition> rememberedSearch_;  // rememberSearch()
  std::uint64_t topologyVersion_ = 1;
  // Counts prepare() calls: points evaluated since the last one carry this number.
  std::uint64_t evaluationPass_ = 0;
  // The pass at the last commit or restore: the next one evaluates the step's first iterate.
  std::uint64_t passAtStepStart_ = 0;
  // The time of the last prepare() (at a commit: the converged time), and the times of the last
  // two commits, t_n and t_(n-1), which the points' gap histories belong to.
  double preparedTime_ = 0;
  double gapTime_ = 0;
  double previousGapTime_ = 0;
  // commitStep(): penetrationWarning()'s record.
  void watchPenetration();
  double deepestPenetration_ = 0;
  double deepestPenetrationTime_ = 0;
  bool holdsClosedAtPrediction(const PointHistory& history, const AssemblyState& state) const;
  bool retryingStep_ = false;  // restored since the last commit: a step's retry holds no point
  bool evaluatedThisPass(const PairPoint& point) const {
    return point.evaluatedInPass == evaluationPass_;
  }
  // STAS
  RigidSurface surface_;
  SurfaceMotion motion_;
  Eigen::Vector3d surfaceOffset_ = Eigen::Vector3d::Zero();
  bool historyInitialized_ = false;
  // Smoothed master: the start-of-step time the nodal normals were computed for.
  double normalsTime_ = 0;
  bool normalsReady_ = false;
  // integration=segments: the slave faces, and the start-of-step time the points were made for.
  FaceSet slaveFaces_;
  double segmentsTime_ = 0;
  bool segmentsReady_ = false;
  int augmentations_ = 0;                // Uzawa updates in the current step
  AndersonAcceleration accelerator_{0};  // of the Uzawa updates; reset at commit and cut-back
  std::string lastAugmentationMessage_;
  std::string augmentationNote_;
  std::vector<double> updateRatios_;  // this step's multiplier update / normal force, per update
  double stepDissipation_ = 0;
  double dissipatedEnergy_ = 0;  // since the start of the run (restart data since session 51)
};

}  // namespace cc::contact
