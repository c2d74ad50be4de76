// Contact pairs on small hand-built surfaces: uniform pressure reproduced exactly, search across
// segments, history commit/restore, and the continuity of the tangential traction when a point
// slides across master segment boundaries (parallel translation, eq. (51) + (47), against the
// naive convective update, eq. (75)).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact/contact_pair.hpp"

namespace cc::contact {
namespace {

using Eigen::Matrix3Xd;
using Eigen::Vector3d;

// A structured grid of nx x ny Quad4 faces on [x0, x0+lx] x [y0, y0+ly] at height z, with node
// indices starting at `firstNode`; `up` orients the normals to +z (else -z). Interior nodes are
// shifted by `distortion` along x so that neighbouring segments are parametrized differently.
struct Grid {
  FaceSet faces;
  Matrix3Xd coordinates;
};

Grid makeGrid(int nx, int ny, double x0, double y0, double lx, double ly, double z, bool up,
              int firstNode, double distortion = 0) {
  Grid g;
  g.coordinates.resize(3, (nx + 1) * (ny + 1));
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      double x = x0 + lx * i / nx;
      const double y = y0 + ly * j / ny;
      if (i > 0 && i < nx) x += distortion * ((i + j) % 2 == 0 ? 1 : -1) * lx / nx;
      g.coordinates.col(j * (nx + 1) + i) = Vector3d(x, y, z);
    }
  }
  g.faces.type = CellType::Quad4;
  g.faces.connectivity.resize(nx * ny, 4);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = firstNode + j * (nx + 1) + i;
      const int b = a + 1, c = a + nx + 2, d = a + nx + 1;
      if (up) {
        g.faces.connectivity.row(j * nx + i) << a, b, c, d;
      } else {
        g.faces.connectivity.row(j * nx + i) << a, d, c, b;
      }
    }
  }
  return g;
}

struct TwoSurfaces {
  Mesh mesh;
  FaceSet master, slave;
};

// Master: 2 x 2 faces on [0,2]^2 at z = 0, normal +z. Slave: 3 x 3 faces on [0,2]^2 at z = -g,
// normal -z (non-matching meshes).
TwoSurfaces overlappingSquares(double penetration) {
  const Grid master = makeGrid(2, 2, 0, 0, 2, 2, 0, true, 0);
  const Grid slave = makeGrid(3, 3, 0, 0, 2, 2, -penetration, false, 9);
  TwoSurfaces s;
  s.mesh.coordinates.resize(3, 9 + 16);
  s.mesh.coordinates << master.coordinates, slave.coordinates;
  s.master = master.faces;
  s.slave = slave.faces;
  return s;
}

ContactPairConfig config(PointKind kind, double friction = 0) {
  ContactPairConfig c;
  c.name = "pair";
  c.kind = kind;
  c.law = {1.0e3, 1.0e3, friction};
  c.integrationPoints = 2;
  return c;
}

struct Evaluation {
  Eigen::VectorXd force;  // 3 * numNodes
};

// Sums the pair's item forces into a global vector at configuration x.
Eigen::VectorXd assembleForce(ContactPair& pair, const Matrix3Xd& x, const Matrix3Xd& previous,
                              double time, bool extrapolatedStart = false) {
  AssemblyState state{time, time - 1, &x, &x, &previous, extrapolatedStart};
  EXPECT_TRUE(pair.prepare(state).ok);
  Eigen::VectorXd global = Eigen::VectorXd::Zero(3 * x.cols());
  for (std::size_t i = 0; i < pair.itemCount(); ++i) {
    const auto nodes = pair.itemNodes(i);
    Eigen::VectorXd force = Eigen::VectorXd::Zero(3 * nodes.size());
    EXPECT_TRUE(pair.evaluate(i, state, force, nullptr).ok);
    for (std::size_t k = 0; k < nodes.size(); ++k)
      global.segment<3>(3 * nodes[k]) += force.segment<3>(3 * k);
  }
  return global;
}

// Uniform penetration g over the slave area A: the total normal force is eps_N g A exactly,
// for STS (Gauss points) and NTS (tributary areas), and each node's share matches.
TEST(ContactPair, UniformPenetrationGivesExactTotalForce) {
  const double g = 1e-3, area = 4.0;
  for (PointKind kind : {PointKind::SegmentToSegment, PointKind::NodeToSegment}) {
    TwoSurfaces s = overlappingSquares(g);
    auto pair = kind == PointKind::SegmentToSegment
                    ? ContactPair::segmentToSegment(config(kind), s.master, s.slave)
                    : ContactPair::nodeToSegment(config(kind), s.mesh, s.master, s.slave);
    const Eigen::VectorXd force = assembleForce(*pair, s.mesh.coordinates, s.mesh.coordinates, 1);
    Vector3d masterTotal = Vector3d::Zero(), slaveTotal = Vector3d::Zero();
    for (int node = 0; node < 9; ++node) masterTotal += force.segment<3>(3 * node);
    for (int node = 9; node < 25; ++node) slaveTotal += force.segment<3>(3 * node);
    // Internal-force convention: the slave's share is N n w with N = -eps_N g, n = +z.
    EXPECT_NEAR(slaveTotal.z(), -1.0e3 * g * area, 1e-12);
    EXPECT_NEAR(masterTotal.z(), 1.0e3 * g * area, 1e-12);
    EXPECT_NEAR(slaveTotal.head<2>().norm(), 0.0, 1e-14);
    const ContactPairRecord record = pair->record();
    EXPECT_NEAR(record.totalForce.z(), 1.0e3 * g * area, 1e-12);  // pushes the slave down... out
    for (int i = 0; i < record.gap.size(); ++i) EXPECT_NEAR(record.gap[i], -g, 1e-15);
  }
}

// A point whose closest-point projection breaks down on its own segment (here the segment has
// collapsed to a point, so its metric is singular) and that no other segment holds makes the
// step fail with ProjectionFailure, so that the step is cut back instead of the point being
// dropped as open. A point that merely leaves the master surface is no failure.
TEST(ContactPair, ProjectionBreakdownOnItsOwnSegmentFailsTheStep) {
  for (PointKind kind : {PointKind::SegmentToSegment, PointKind::NodeToSegment}) {
    TwoSurfaces s = overlappingSquares(1e-3);
    auto pair = kind == PointKind::SegmentToSegment
                    ? ContactPair::segmentToSegment(config(kind), s.master, s.slave)
                    : ContactPair::nodeToSegment(config(kind), s.mesh, s.master, s.slave);
    const Matrix3Xd start = s.mesh.coordinates;
    assembleForce(*pair, start, start, 1);  // every point finds its segment
    pair->commitStep();

    Matrix3Xd collapsed = start;  // master segment 0 (nodes 0, 1, 4, 3) shrinks to one point
    for (int node : {0, 1, 3, 4}) collapsed.col(node) = Vector3d(0.5, 0.5, 0);
    AssemblyState collapsedState{2, 1, &collapsed, &collapsed, &start};
    const LocalStatus status = pair->prepare(collapsedState);
    EXPECT_FALSE(status.ok);
    EXPECT_EQ(status.kind, FailureKind::ProjectionFailure);
    EXPECT_NE(status.detail.find("broke down"), std::string::npos) << status.detail;
    pair->restoreStep();

    Matrix3Xd shifted = start;  // the master moves away sideways: points leave, no failure
    for (int node = 0; node < 9; ++node) shifted(0, node) += 10;
    AssemblyState shiftedState{2, 1, &shifted, &shifted, &start};
    EXPECT_TRUE(pair->prepare(shiftedState).ok);
    for (std::size_t i = 0; i < pair->itemCount(); ++i) {
      Eigen::VectorXd force = Eigen::VectorXd::Zero(3 * pair->itemNodes(i).size());
      EXPECT_TRUE(pair->evaluate(i, shiftedState, force, nullptr).ok);
      EXPECT_EQ(force.norm(), 0.0);
    }
  }
}

// A slave node dragged along a strip of 6 distorted master segments in 30 steps: the search
// keeps it on the right segment, and in full sliding the traction stays mu N in magnitude and
// direction (parallel translation); the convective update (75) jumps where the node changes
// segment, because the segments' parameters differ in scale.
std::vector<double> tractionAlongPath(TangentialIntegration integration, int* segmentChanges) {
  const double g = 2e-3;
  Grid master = makeGrid(6, 1, 0, 0, 6, 1, 0, true, 0, 0.3);
  Grid slave = makeGrid(1, 1, 0.2, 0.3, 0.2, 0.2, -g, false, 14);
  Mesh mesh;
  mesh.coordinates.resize(3, 14 + 4);
  mesh.coordinates << master.coordinates, slave.coordinates;
  ContactPairConfig c = config(PointKind::NodeToSegment, 0.3);
  c.law.integration = integration;
  auto pair = ContactPair::nodeToSegment(c, mesh, master.faces, slave.faces);
  Matrix3Xd previous = mesh.coordinates;
  std::vector<double> tractions;
  int lastSegmentSum = -1;
  *segmentChanges = 0;
  for (int step = 1; step <= 30; ++step) {
    Matrix3Xd x = mesh.coordinates;
    for (int node = 14; node < 18; ++node) x(0, node) += 0.18 * step;
    assembleForce(*pair, x, previous, step);
    pair->commitStep();
    const ContactPairRecord r = pair->record();
    double sum = 0;
    for (int i = 0; i < r.tangentialTraction.cols(); ++i) sum += r.tangentialTraction(0, i);
    tractions.push_back(sum);
    int segmentSum = 0;
    for (std::size_t i = 0; i < pair->itemCount(); ++i)
      segmentSum += static_cast<int>(pair->itemNodes(i)[1]);
    if (lastSegmentSum >= 0 && segmentSum != lastSegmentSum) ++*segmentChanges;
    lastSegmentSum = segmentSum;
    previous = x;
  }
  return tractions;
}

TEST(ContactPair, ParallelTranslationKeepsTractionContinuousAcrossSegments) {
  int changes = 0;
  const std::vector<double> parallel =
      tractionAlongPath(TangentialIntegration::ParallelTranslation, &changes);
  EXPECT_GE(changes, 4);  // the nodes crossed several segment boundaries
  // Full sliding from the second step on: |T| = mu |N| = 0.3 * 1e3 * 2e-3 per node, 4 nodes,
  // opposing the motion (+x) of the slave.
  for (std::size_t k = 1; k < parallel.size(); ++k) EXPECT_NEAR(parallel[k], -4 * 0.6, 1e-12);
  const std::vector<double> convective =
      tractionAlongPath(TangentialIntegration::Convective, &changes);
  double largestJump = 0;
  for (std::size_t k = 2; k < convective.size(); ++k) {
    largestJump = std::max(largestJump, std::abs(convective[k] - convective[k - 1]));
  }
  EXPECT_GT(largestJump, 0.5);
}

// The first iterate of a step after a sliding step (issue 14): a point that was sliding and
// whose trial traction lies just inside the Coulomb cone (here N grew by `growth` since the
// converged state while T^(n) was carried unchanged) keeps sliding if the gap to the cone is
// within kStepStartSlideBand of mu |N|; from the second iterate on, and beyond the band, it
// sticks, as the return mapping (79) says.
std::vector<ContactState> statesAtStepStart(double growth, int evaluations, bool restore) {
  const double g = 2e-3;
  Grid master = makeGrid(6, 1, 0, 0, 6, 1, 0, true, 0);
  Grid slave = makeGrid(1, 1, 0.2, 0.3, 0.2, 0.2, -g, false, 14);
  Mesh mesh;
  mesh.coordinates.resize(3, 14 + 4);
  mesh.coordinates << master.coordinates, slave.coordinates;
  auto pair = ContactPair::nodeToSegment(config(PointKind::NodeToSegment, 0.3), mesh, master.faces,
                                         slave.faces);
  Matrix3Xd slid = mesh.coordinates;
  for (int node = 14; node < 18; ++node) slid(0, node) += 0.18;
  assembleForce(*pair, slid, mesh.coordinates, 1);
  pair->commitStep();
  for (int i = 0; i < pair->record().state.size(); ++i)
    EXPECT_EQ(pair->record().state[i], static_cast<int>(ContactState::Slip));
  Matrix3Xd pressed = slid;
  for (int node = 14; node < 18; ++node) pressed(2, node) -= growth * g;
  for (int k = 0; k < evaluations; ++k) assembleForce(*pair, pressed, slid, 2);
  if (restore) {
    pair->restoreStep();
    assembleForce(*pair, pressed, slid, 2);
  }
  std::vector<ContactState> states;
  const ContactPairRecord r = pair->record();
  for (int i = 0; i < r.state.size(); ++i) states.push_back(static_cast<ContactState>(r.state[i]));
  return states;
}

TEST(ContactPair, ASlidingPointKeepsSlidingAtTheStepStartOnlyWithinTheBand) {
  const double inside = 0.1 * kStepStartSlideBand;  // trial inside the cone by a tenth of it
  for (const ContactState state : statesAtStepStart(inside, 1, false))
    EXPECT_EQ(state, ContactState::Slip) << "first iterate, within the band";
  for (const ContactState state : statesAtStepStart(inside, 2, false))
    EXPECT_EQ(state, ContactState::Stick) << "second iterate: the exact decision";
  for (const ContactState state : statesAtStepStart(inside, 2, true))
    EXPECT_EQ(state, ContactState::Slip) << "first iterate of the step retried after a restore";
  for (const ContactState state : statesAtStepStart(5 * kStepStartSlideBand, 1, false))
    EXPECT_EQ(state, ContactState::Stick) << "first iterate, beyond the band";
}

// STAS at the step's first iterate (issue 14): the rigid surface's motion over the step enters
// linearly, f(x, s_n+1) ~ f(x, s_n) - K(x, s_n) ds; from the second iterate on the force is the
// exact one. A rigid plane over a 2 x 2 master square (area 4) penetrating it by g, moved along
// its normal by `move` over the step (positive: away from the body); returns the total normal
// force at the first and at the second evaluation of the step. `extrapolatedStart`: the first
// iterate comes from Newton's extrapolating predictor (the bodies have moved already).
std::pair<double, double> rigidPlaneForces(double g, double move, bool extrapolatedStart = false) {
  const Grid body = makeGrid(2, 2, 0, 0, 2, 2, 0, true, 0);
  RigidSurface plane;
  plane.shape = RigidSurface::Shape::Plane;
  plane.origin = Vector3d(0, 0, -g);
  plane.normal = -Vector3d::UnitZ();  // towards the body below z = 0
  auto pair =
      ContactPair::segmentToAnalytical(config(PointKind::SegmentToAnalytical), body.faces, plane,
                                       [move](double time) { return Vector3d(0, 0, move * time); });
  const Matrix3Xd& x = body.coordinates;
  double first = 0, second = 0;
  const Eigen::VectorXd f1 = assembleForce(*pair, x, x, 1, extrapolatedStart);
  const Eigen::VectorXd f2 = assembleForce(*pair, x, x, 1);
  for (int node = 0; node < x.cols(); ++node) {
    first += f1[3 * node + 2];
    second += f2[3 * node + 2];
  }
  return {first, second};
}

TEST(ContactPair, RigidSurfaceMotionEntersTheStepsFirstIterateLinearly) {
  const double g = 1e-3, pushing = 1e3 * g * 4;  // eps_N g A
  const auto [still, stillAgain] = rigidPlaneForces(g, 0);
  EXPECT_NEAR(std::abs(still), pushing, 1e-9 * pushing);
  EXPECT_NEAR(stillAgain, still, 1e-12 * pushing);
  // Pressed deeper by g: linear in the gap, so the prediction is the exact force 2 eps_N g A.
  const auto [deeper, deeperAgain] = rigidPlaneForces(g, -g);
  EXPECT_NEAR(deeper, 2 * still, 1e-9 * pushing);
  EXPECT_NEAR(deeperAgain, 2 * still, 1e-9 * pushing);
  // Lifted by 2g: the exact surface leaves the body (no force); the first iterate's prediction
  // is the linear extrapolation -eps_N g A, a pull, as a meshed die's first iterate would be.
  const auto [lifted, liftedAgain] = rigidPlaneForces(g, 2 * g);
  EXPECT_NEAR(lifted, -still, 1e-9 * pushing);
  EXPECT_EQ(liftedAgain, 0.0);
}

// With Newton's extrapolating predictor the first iterate already carries the last step's motion,
// so the surface is evaluated where it stands at the step's end: the lifted plane gives the exact
// 0 at once (the linear prediction above would pull with -eps_N g A).
TEST(ContactPair, RigidSurfaceIsExactAtAnExtrapolatedFirstIterate) {
  const double g = 1e-3, pushing = 1e3 * g * 4;  // eps_N g A
  const auto [lifted, liftedAgain] = rigidPlaneForces(g, 2 * g, true);
  EXPECT_EQ(lifted, 0.0);
  EXPECT_EQ(liftedAgain, 0.0);
  const double still = rigidPlaneForces(g, 0).first;
  const auto [deeper, deeperAgain] = rigidPlaneForces(g, -g, true);
  EXPECT_NEAR(deeper, 2 * still, 1e-9 * pushing);
  EXPECT_NEAR(deeperAgain, 2 * still, 1e-9 * pushing);
}

// A roof of two flat master faces meeting at a ridge x = 1 (z = 0.2 x, then 0.2 (2 - x)); below
// the ridge a slave node projects inside both faces, and the search keeps it on the one it
// came from. Newton's line search recalls the search state of its iterate before each trial
// (nonlinear_problem.hpp): a trial that moved the node to the other face must not decide the
// face of the next trial near the iterate, else the residual along the Newton direction jumps
// by the change of the normal (issue 14, the faceted ironing die with mu = 0.6).
TEST(ContactPair, RecalledSearchEvaluatesTheIterateOnItsOwnFaceAgain) {
  Mesh mesh;
  mesh.coordinates.resize(3, 10);
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 3; ++i) mesh.coordinates.col(3 * j + i) = Vector3d(i, j, i == 1 ? 0.2 : 0);
  }
  FaceSet master;
  master.type = CellType::Quad4;
  master.connectivity.resize(2, 4);
  master.connectivity << 0, 1, 4, 3, 1, 2, 5, 4;
  // One slave face; only node 6 lies over the master, its other nodes far beside it (open).
  const Vector3d iterate(0.99, 0.5, 0.12);
  mesh.coordinates.col(6) = iterate;
  mesh.coordinates.col(7) = Vector3d(5, 0.5, 0.12);
  mesh.coordinates.col(8) = Vector3d(5, 1.5, 0.12);
  mesh.coordinates.col(9) = Vector3d(0.99, 1.5, 5);
  FaceSet slave;
  slave.type = CellType::Quad4;
  slave.connectivity.resize(1, 4);
  slave.connectivity << 6, 9, 8, 7;
  auto pair = ContactPair::nodeToSegment(config(PointKind::NodeToSegment), mesh, master, slave);
  Matrix3Xd x = mesh.coordinates;
  const Eigen::VectorXd atIterate = assembleForce(*pair, x, mesh.coordinates, 1);
  ASSERT_GT(atIterate.norm(), 0);  // node 6 penetrates
  pair->rememberSearch();
  x.col(6) = Vector3d(1.2, 0.5, 0.12);  // a long trial: the node is under the other face only
  (void)assembleForce(*pair, x, mesh.coordinates, 1);
  x.col(6) = iterate;
  const Eigen::VectorXd fromOtherFace = assembleForce(*pair, x, mesh.coordinates, 1);
  EXPECT_GT((fromOtherFace - atIterate).norm(), 0.05 * atIterate.norm());  // the hysteresis
  pair->recallSearch();
  const Eigen::VectorXd recalled = assembleForce(*pair, x, mesh.coordinates, 1);
  EXPECT_EQ((recalled - atIterate).norm(), 0.0);
}

// A failed Newton solve names the points that kept switching (issue 14): the pair counts each
// point's state changes between the calls of takeChanges() since the last commit or restore, and
// names a point by its slave node (NTS: its own node; STS: the node of largest shape value).
TEST(ContactPair, CountsEachPointsStateChangesInTheAttemptAndNamesItsSlaveNode) {
  for (PointKind kind : {PointKind::NodeToSegment, PointKind::SegmentToSegment}) {
    TwoSurfaces s = overlappingSquares(1e-3);
    auto pair = kind == PointKind::NodeToSegment
                    ? ContactPair::nodeToSegment(config(kind), s.mesh, s.master, s.slave)
                    : ContactPair::segmentToSegment(config(kind), s.master, s.slave);
    const Matrix3Xd closed = s.mesh.coordinates;
    Matrix3Xd open = closed;
    for (int node = 9; node < 25; ++node) open(2, node) = 0.1;  // lifted off the master
    const int points = pair->pointCount();
    int changes = 0;
    for (const Matrix3Xd* x : std::vector<const Matrix3Xd*>{&closed, &open, &closed}) {
      (void)assembleForce(*pair, *x, s.mesh.coordinates, 1);
      EXPECT_EQ(pair->takeChanges().state, points);  // every point opens or closes
      ++changes;
      const std::vector<int>& counted = pair->stateChangesInAttempt();
      ASSERT_EQ(counted.size(), static_cast<std::size_t>(points));
      EXPECT_TRUE(std::all_of(counted.begin(), counted.end(), [&](int c) { return c == changes; }));
      EXPECT_TRUE(std::all_of(pair->segmentChangesInAttempt().begin(),
                              pair->segmentChangesInAttempt().end(), [](int c) { return c == 0; }));
    }
    std::vector<int> named;
    for (int i = 0; i < points; ++i) {
      const int node = pair->nearestNode(static_cast<std::size_t>(i));
      EXPECT_GE(node, 9);  // a slave node
      EXPECT_LT(node, 25);
      named.push_back(node);
    }
    if (kind == PointKind::NodeToSegment) {  // each point names its own node
      std::sort(named.begin(), named.end());
      EXPECT_EQ(std::unique(named.begin(), named.end()), named.end());
    }
    pair->restoreStep();
    const std::vector<int>& forgotten = pair->stateChangesInAttempt();
    EXPECT_TRUE(std::all_of(forgotten.begin(), forgotten.end(), [](int c) { return c == 0; }));
  }
}

// Newton's extrapolating predictor can open a point under a stiff penalty that stays in contact
// (issue 14, the stiff ball): a point closed at the last two converged steps whose gap,
// extrapolated like the displacements, stays closed keeps N = eps_N g at the predicted iterate,
// a tension where that iterate opens it; at the next iterate, at a first iterate that is not
// extrapolated and in the retry of a failed step, the law is the paper's again. A gap history that
// extrapolates to an opening does not hold the point, and the history survives a restart.
TEST(ContactPair, AnExtrapolatedIterateHoldsAPointClosedThatItsGapHistoryKeepsClosed) {
  const double area = 4.0, penalty = 1.0e3, lifted = 1e-4;
  for (PointKind kind : {PointKind::SegmentToSegment, PointKind::NodeToSegment}) {
    for (const double secondPenetration : {1.5e-3, 0.4e-3}) {  // extrapolates to -1e-3, +2e-4
      TwoSurfaces s = overlappingSquares(2e-3);
      auto make = [&] {
        return kind == PointKind::SegmentToSegment
                   ? ContactPair::segmentToSegment(config(kind), s.master, s.slave)
                   : ContactPair::nodeToSegment(config(kind), s.mesh, s.master, s.slave);
      };
      auto pair = make();
      auto atHeight = [&](double z) {
        Matrix3Xd x = s.mesh.coordinates;
        for (int node = 9; node < 25; ++node) x(2, node) = z;
        return x;
      };
      const Matrix3Xd first = atHeight(-2e-3), second = atHeight(-secondPenetration);
      (void)assembleForce(*pair, first, s.mesh.coordinates, 1);
      pair->commitStep();
      (void)assembleForce(*pair, second, first, 2);
      pair->commitStep();
      auto slaveForceZ = [&](ContactPair& p, double time, bool extrapolated) {
        const Eigen::VectorXd force =
            assembleForce(p, atHeight(lifted), second, time, extrapolated);
        double total = 0;
        for (int node = 9; node < 25; ++node) total += force[3 * node + 2];
        return total;
      };
      const bool held = secondPenetration > 1e-3;
      // The slave's share of the force is N n w with n = +z: eps_N g A, a pull towards the master.
      EXPECT_NEAR(slaveForceZ(*pair, 3, true), held ? penalty * lifted * area : 0.0, 1e-12);
      EXPECT_EQ(slaveForceZ(*pair, 3, true), 0.0);  // the second iterate: open
      pair->restoreStep();
      EXPECT_EQ(slaveForceZ(*pair, 3, false), 0.0);  // a first iterate that is not extrapolated
      pair->restoreStep();
      EXPECT_EQ(slaveForceZ(*pair, 3, true), 0.0);  // the retry of a failed step
      auto restarted = make();
      restarted->importHistory(pair->exportHistory());
      EXPECT_NEAR(slaveForceZ(*restarted, 3, true), held ? penalty * lifted * area : 0.0, 1e-12);
    }
  }
}

// A held point continues the closed branch linearly through g = 0, its friction too: at a
// predicted iterate lifted by delta the held sliding point carries exactly the negative of the
// force it carries at a penetration delta with the same slip, friction included. The bound
// mu |N| instead grew as the point opened and pushed its friction the wrong way: the first
// Newton update of the stiff ball with friction went 5 times too far (issue 14).
TEST(ContactPair, AHeldSlidingPointContinuesTheClosedBranchFrictionIncluded) {
  const double delta = 1e-4, friction = 0.3;
  for (PointKind kind : {PointKind::SegmentToSegment, PointKind::NodeToSegment}) {
    TwoSurfaces s = overlappingSquares(2e-3);
    auto make = [&] {
      return kind == PointKind::SegmentToSegment
                 ? ContactPair::segmentToSegment(config(kind, friction), s.master, s.slave)
                 : ContactPair::nodeToSegment(config(kind, friction), s.mesh, s.master, s.slave);
    };
    auto at = [&](double z, double slide) {  // the slave lowered to z and slid along x
      Matrix3Xd x = s.mesh.coordinates;
      for (int node = 9; node < 25; ++node) {
        x(2, node) = z;
        x(0, node) += slide;
      }
      return x;
    };
    auto pair = make();
    const Matrix3Xd first = at(-2e-3, 0.0), second = at(-1.5e-3, 0.01);
    (void)assembleForce(*pair, first, s.mesh.coordinates, 1);
    pair->commitStep();
    (void)assembleForce(*pair, second, first, 2);  // eps_T 0.01 = 10 > mu |N|: sliding
    pair->commitStep();
    auto predicted = [&](double z) {
      auto fresh = make();
      fresh->importHistory(pair->exportHistory());
      return assembleForce(*fresh, at(z, 0.02), second, 3, true);
    };
    const Eigen::VectorXd closed = predicted(-delta), held = predicted(delta);
    double tangential = 0;
    for (int node = 9; node < 25; ++node) tangential += std::abs(closed[3 * node]);
    EXPECT_GT(tangential, 0.5 * friction * 1e3 * delta * 4.0);  // friction acts: mu eps_N g A
    EXPECT_LT((held + closed).norm(), 1e-12 * closed.norm());
  }
}

// A restart table that does not fit the pair is refused with a message naming the pair and
// what was expected, before the run continues from it; a table that fits restores the pair's
// force exactly (the restart tests above).
TEST(ContactPair, RefusesAHistoryTableThatDoesNotFitThePair) {
  TwoSurfaces s = overlappingSquares(2e-3);
  auto pair = ContactPair::segmentToSegment(config(PointKind::SegmentToSegment), s.master, s.slave);
  (void)assembleForce(*pair, s.mesh.coordinates, s.mesh.coordinates, 1);
  pair->commitStep();
  const Eigen::MatrixXd table = pair->exportHistory();
  auto messageOf = [&](const Eigen::MatrixXd& stored) {
    auto restarted =
        ContactPair::segmentToSegment(config(PointKind::SegmentToSegment), s.master, s.slave);
    try {
      restarted->importHistory(stored);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(messageOf(table), "accepted");
  const Eigen::MatrixXd missingPoint = table.leftCols(table.cols() - 1);
  EXPECT_NE(messageOf(missingPoint)
                .find(fmt::format("history table is {} x {}, expected {} x {}", table.rows(),
                                  table.cols() - 1, table.rows(), table.cols())),
            std::string::npos)
      << messageOf(missingPoint);
  Eigen::MatrixXd beyondTheMaster = table;
  beyondTheMaster(1, 2) = 99;  // the committed segment of point 2 (HistoryRow kSegment)
  EXPECT_NE(messageOf(beyondTheMaster).find("point 2: master segment 99 does not exist"),
            std::string::npos)
      << messageOf(beyondTheMaster);
}

}  // namespace
}  // namespace cc::contact
