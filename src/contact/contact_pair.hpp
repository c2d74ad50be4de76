// A contact pair as a Contribution to the global system: its contact points (slave nodes for
// NTS, slave Gauss points for STS, master Gauss points against a rigid surface for STAS), the
// segment search that keeps every point on the master segment it projects onto, the point
// history (xi, rho, T, state, accumulated slip) committed only when a step converges, and the
// per-step output record.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "contact/master_surface.hpp"
#include "contact/point_evaluation.hpp"
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
  LocalStatus prepare(const AssemblyState& state) override;
  std::size_t itemCount() const override { return points_.size(); }
  std::span<const int> itemNodes(std::size_t item) const override { return points_[item].nodes; }
  std::uint64_t topologyVersion() const override { return topologyVersion_; }
  LocalStatus evaluate(std::size_t item, const AssemblyState& state, Eigen::VectorXd& force,
                       Eigen::MatrixXd* tangent) override;
  bool tangentSymmetric() const override;
  void commitStep() override;
  void restoreStep() override;

  // Output of the last evaluated (after commit: converged) state.
  ContactPairRecord record() const;

  // Augmented Lagrangian (contact_pair_augmentation.cpp): after a converged Newton solve, checks
  // the stopping rule and otherwise updates the multipliers (Uzawa) for another solve.
  enum class Augmentation { Converged, Updated, Failed };
  Augmentation augment();
  const std::string& augmentationMessage() const { return lastAugmentationMessage_; }
  int augmentations() const { return augmentations_; }

  // Energy (contact_pair_energy.cpp): the stored penalty energy of the last evaluated state, and
  // the frictional dissipation of the last committed step and since the start of the run.
  double penaltyEnergy() const;
  double stepDissipation() const { return stepDissipation_; }
  double dissipatedEnergy() const { return dissipatedEnergy_; }

  // Restart (contact_pair_history.cpp): the committed history of every point and the search
  // state it continues from, one column of kHistoryRows numbers per point, and its
  // restoration. importHistory throws std::invalid_argument if the table does not fit the pair.
  static constexpr int kHistoryRows = 20;
  Eigen::MatrixXd exportHistory() const;
  void importHistory(const Eigen::MatrixXd& table);
  const ContactPairConfig& config() const { return config_; }
  int pointCount() const { return static_cast<int>(points_.size()); }

 private:
  // What the last evaluation found at a point (the trial state of the current iteration).
  struct Trial {
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

  struct Point {
    // Slave side (fixed): nodes and shape values at the point; NTS area or STS Gauss point.
    int slaveCount = 0;
    std::array<int, 9> slaveNodes{};
    std::array<double, 9> slaveShape{};
    SlaveSide slave;
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
    // The item: node list and where the slave/master/previous-master nodes sit in it.
    std::vector<int> nodes;
    PointLayout layout;
    PointHistory committed;
    Trial trial;
    // Augmented Lagrangian: lambda_N of the current Uzawa update and of the last commit, and
    // the tangential augmentation added to T^(n) during this step (reset at commit, when
    // T^(n+1) takes it over).
    double multiplierNormal = 0;
    double committedMultiplierNormal = 0;
    Eigen::Vector3d tractionAugmentation = Eigen::Vector3d::Zero();
  };

  ContactPair(ContactPairConfig config, const FaceSet& master);
  void buildItem(Point& point) const;
  Eigen::Vector3d slavePosition(const Point& point, const Eigen::Matrix3Xd& x) const;
  // Assigns every point its master segment (local walk, then the global search). Fails with
  // ProjectionFailure when a point's projection broke down on its own segment and no other
  // segment holds it: treating it as open could drop a point that is in contact.
  LocalStatus searchSegments(const Eigen::Matrix3Xd& x, double time);
  // Table 1, step 1: the projections in the initial configuration start the history.
  void initializeHistory(const AssemblyState& state);
  PointSetup setupFor(const Point& point) const;
  static void storeTrial(Point& point, const PointEvaluation& evaluation, const LawParameters& law);
  // Dissipation w mu |N| Delta lambda of a point's trial state (contact_pair_energy.cpp).
  double pointDissipation(const Trial& trial) const;
  void accountDissipation();  // at commit: adds the step's dissipation to the run's
  // At commit / cut-back: the multipliers of the step become committed / are forgotten.
  void commitAugmentation();
  void restoreAugmentation();

  ContactPairConfig config_;
  MasterSurface master_;
  std::vector<Point> points_;
  std::uint64_t topologyVersion_ = 1;
  // STAS
  RigidSurface surface_;
  SurfaceMotion motion_;
  Eigen::Vector3d surfaceOffset_ = Eigen::Vector3d::Zero();
  // The search grid is rebuilt once per step attempt (the master moves between steps).
  double gridTime_ = -1;
  bool historyInitialized_ = false;
  int augmentations_ = 0;  // Uzawa updates in the current step
  std::string lastAugmentationMessage_;
  double stepDissipation_ = 0;
  double dissipatedEnergy_ = 0;  // since the start of this run (not part of the restart data)
};

}  // namespace cc::contact
