// Boundary conditions of whole decks (issue 15): the built-in node set `all` (plane strain with
// one line, `fix all uz`) checked against the closed-form St. Venant-Kirchhoff plane-strain
// stretch, and the rule for two conditions on one dof (the same value at every step time:
// accepted, the run unchanged bit for bit; different: refused naming both deck lines).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "deck_runner.hpp"
#include "model/boundary_conditions.hpp"

namespace cc::test {
namespace {

// Decks of these tests are parsed as if they were tests/unit/model/<name>.deck, so that the
// meshes of the repository resolve as "../../../meshes/...".
std::string virtualPath(const std::string& name) {
  return std::string(COVCONTACT_SOURCE_DIR) + "/tests/unit/model/" + name;
}

// The unit cube (cube_boundary.geo: faces xmin ... zmax; distorted elements, plane faces) of E =
// 100, nu = 0.3, stretched in x by `stretch` - 1 at t = 1 with y free to contract: the lines after
// `elements` supply the supports.
std::string stretchDeck(const std::string& supports, double stretch) {
  return "mesh \"../../../meshes/cube_boundary.geo\" n=2 distort=0.5\n"
         "material m svk E=100 nu=0.3\n"
         "elements cube hex8 material=m\n" +
         supports + "prescribe xmax ux \"" + std::to_string(stretch - 1) +
         "*t\"\n"
         "solve\n"
         "  steps 2 dt=0.5\n"
         "end\n";
}

// Closed form of the homogeneous plane-strain stretch of a St. Venant-Kirchhoff block:
// F = diag(lx, ly, 1), E = (F^T F - I) / 2, S = lambda tr(E) I + 2 mu E with S_yy = 0, so
// E_yy = -lambda / (lambda + 2 mu) E_xx. Nominal forces on the unit faces: P_xx = lx S_xx on
// xmax, P_zz = S_zz on zmax (the force that keeps the thickness, which a plane-stress block
// would not need).
struct PlaneStrainStretch {
  double transverseStretch;  // ly
  double forceX;             // lx S_xx
  double forceZ;             // S_zz
};

PlaneStrainStretch planeStrainStretch(double youngsModulus, double poissonRatio, double stretch) {
  const double lambda =
      youngsModulus * poissonRatio / ((1 + poissonRatio) * (1 - 2 * poissonRatio));
  const double mu = youngsModulus / (2 * (1 + poissonRatio));
  const double exx = 0.5 * (stretch * stretch - 1);
  const double eyy = -lambda / (lambda + 2 * mu) * exx;
  return {std::sqrt(1 + 2 * eyy), stretch * (lambda * (exx + eyy) + 2 * mu * exx),
          lambda * (exx + eyy)};
}

// Newton stops at an energy norm 1e-16 of the first iteration's (NewtonSpec default), i.e. a
// displacement error of at most ~1e-8 of the increment; forces follow the displacements through
// a stiffness of order E. A wrong support (uz left free: plane stress) changes P_xx by nu^2 ~ 9 %
// and P_zz from 6.6 to 0.
constexpr double kNewtonTolerance = 1e-8;

TEST(ModelAllSet, FixAllUzGivesThePlaneStrainStretch) {
  const double stretch = 1.01;
  const DeckRun run = runDeckText(stretchDeck("fix all uz\nfix xmin ux\nfix ymin uy\n", stretch),
                                  virtualPath("plane_strain.deck"));
  ASSERT_EQ(run.steps.size(), 2u);
  const RecordedStep& last = run.steps.back();
  const PlaneStrainStretch exact = planeStrainStretch(100, 0.3, stretch);
  const Mesh& mesh = run.model->mesh();
  ASSERT_EQ(mesh.nodeSets.at("all").nodes.size(), static_cast<std::size_t>(mesh.numNodes()));
  for (int node = 0; node < mesh.numNodes(); ++node) {
    EXPECT_EQ(last.displacement(2, node), 0.0) << "node " << node;  // fixed, exactly
    EXPECT_NEAR(last.displacement(1, node),
                (exact.transverseStretch - 1) * mesh.coordinates(1, node),
                kNewtonTolerance * (stretch - 1))
        << "node " << node;
  }
  EXPECT_NEAR(last.setReaction("xmax").x(), exact.forceX, kNewtonTolerance * 100);
  EXPECT_NEAR(last.setReaction("xmin").x(), -exact.forceX, kNewtonTolerance * 100);
  double zmaxForce = 0;
  for (int node : mesh.nodeSets.at("zmax").nodes) zmaxForce += last.reaction(2, node);
  EXPECT_NEAR(zmaxForce, exact.forceZ, kNewtonTolerance * 100);
  // What the set `all` carries in total: the out-of-balance force of a body in equilibrium.
  EXPECT_NEAR(last.setReaction("all").norm(), 0.0, kNewtonTolerance * 100);
  // The closed form against small-strain plane strain, sigma_xx = E / (1 - nu^2) eps = 1.0989
  // and sigma_zz = nu sigma_xx = 0.3297 at eps = 0.01: equal to O(eps) (measured 1.5 %, 0.5 %).
  EXPECT_NEAR(exact.forceX / (100 / (1 - 0.3 * 0.3) * 0.01), 1.0, 2 * (stretch - 1));
  EXPECT_NEAR(exact.forceZ / (0.3 * 100 / (1 - 0.3 * 0.3) * 0.01), 1.0, 2 * (stretch - 1));
}

// The same supports written twice in ways that give the same value at every time: fix + fix
// (all and zmin), fix + `prescribe ... 0` and a zero table, and the stretch prescribed again as
// the same motion in another form (commuted, and as a function of x that equals it on xmax).
// Refused before (fix + prescribe); now the run is the single-condition run, bit for bit.
TEST(ModelDoubleConditions, ConditionsGivingTheSameValuesAreAccepted) {
  const double stretch = 1.01;
  const std::string plain = "fix all uz\nfix xmin ux\nfix ymin uy\n";
  const std::string doubled =
      plain +
      "fix zmin uz\nprescribe xmin ux 0\nprescribe zmax uz table (0,0) "
      "(1,0)\nprescribe xmax ux \"t*0.01\"\nprescribe xmax ux \"0.01*t*x\"\n";
  const DeckRun single = runDeckText(stretchDeck(plain, stretch), virtualPath("single.deck"));
  const DeckRun twice = runDeckText(stretchDeck(doubled, stretch), virtualPath("doubled.deck"));
  ASSERT_EQ(twice.steps.size(), 2u);
  EXPECT_EQ(twice.steps.back().displacement, single.steps.back().displacement);
  EXPECT_EQ(twice.steps.back().setReaction("xmin"), single.steps.back().setReaction("xmin"));
  EXPECT_NEAR(twice.steps.back().setReaction("xmin").x(),
              -planeStrainStretch(100, 0.3, stretch).forceX, kNewtonTolerance * 100);
}

std::string refusal(const std::string& supports, const std::string& name) {
  try {
    runDeckText(stretchDeck(supports, 1.01), virtualPath(name));
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "deck ran without error:\n" << stretchDeck(supports, 1.01);
  return "";
}

// A fixed dof prescribed to move: refused at the prescribe line, naming the fix line, the node,
// the time and both values. (Line 4 of the deck: fix all ux; line 7: the stretch of xmax.)
TEST(ModelDoubleConditions, AFixedDofPrescribedToMoveIsRefusedNamingBothLines) {
  const std::string message = refusal("fix all ux\nfix ymin uy\nfix zmin uz\n", "fixed.deck");
  const std::string deck = virtualPath("fixed.deck");
  EXPECT_NE(message.find(deck + ":7:1: error: prescribe 'xmax': ux of gmsh node "),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("at (1, 0, 0) is also fixed by the line at " + deck +
                         ":4:1, which gives 0 at t = 0.25 where this line gives 0.0025"),
            std::string::npos)
      << message;
}

// Two motions that agree at every step end (t = 0, 0.5, 1) but not in between: a cut-back would
// evaluate them at t = 0.25, where they differ by 1e-3, so they are refused there.
TEST(ModelDoubleConditions, MotionsDifferingOnlyBetweenStepEndsAreRefused) {
  const std::string message = refusal(
      "fix xmin ux\nfix ymin uy\nfix zmin uz\n"
      "prescribe xmax ux \"0.01*t + 0.001*sin(2*pi*t)\"\n",
      "between.deck");
  EXPECT_NE(
      message.find(virtualPath("between.deck") + ":8:1: error: prescribe 'xmax': ux of gmsh node "),
      std::string::npos)
      << message;
  EXPECT_NE(message.find("is also prescribed by the line at " + virtualPath("between.deck") +
                         ":7:1, which gives 0.0035 at t = 0.25 where this line gives 0.0025"),
            std::string::npos)
      << message;
}

// Two motions that agree at every time compared before the run (t = 0, 0.5, 1: sin(2 pi t) = 0)
// but not at 0.3, where a cut-back by the factor 0.3 lands: the full step needs more than 4
// Newton iterations (maxit=4), so it is cut back to t = 0.3. Before, the run went on there with
// the first line's value and ended with exit 0 (4 steps, 1 cut-back); now the conditions are
// compared again at every time the run evaluates them, and it stops at t = 0.3 naming both.
TEST(ModelDoubleConditions, ACutBackTimeNotComparedBeforeTheRunIsComparedWhenReached) {
  const std::string deck = virtualPath("cutback.deck");
  const std::string text =
      "mesh \"../../../meshes/cube_boundary.geo\" n=2 distort=0.5\n"
      "material m svk E=100 nu=0.3\n"
      "elements cube hex8 material=m\n"
      "fix all uz\n"
      "fix xmin ux\n"
      "fix ymin uy\n"
      "prescribe xmax ux \"0.2*t\"\n"
      "prescribe xmax ux \"0.2*t + 0.01*sin(2*_pi*t)\"\n"
      "solve\n"
      "  steps 1 dt=1 maxit=4 cutback_factor=0.3\n"
      "end\n";
  std::string message;
  try {
    runDeckText(text, deck);
    ADD_FAILURE() << "the run went through t = 0.3 with two different values of one dof";
  } catch (const InputError& error) {
    message = error.what();
  }
  EXPECT_NE(message.find(deck + ":8:1: error: prescribe 'xmax': ux of gmsh node "),
            std::string::npos)
      << message;
  // 0.2 * 0.3 against 0.06 + 0.01 sin(0.6 pi) = 0.0695105652.
  EXPECT_NE(message.find("is also prescribed by the line at " + deck +
                         ":7:1, which gives 0.06 at t = 0.3 where this line gives 0.069510565"),
            std::string::npos)
      << message;
}

// The times compared: t = 0, every step end and midpoint, bit for bit as the load stepper
// computes them (phase start + k dt); a long phase is thinned to evenly spaced steps and its end.
TEST(ModelDoubleConditions, CheckedTimesAreTheStepEndsAndMidpoints) {
  PhaseSpec first;
  first.steps = 2;
  first.dt = 0.5;
  PhaseSpec second;
  second.steps = 3;
  second.dt = 1;
  EXPECT_EQ(checkedTimes({first, second}, 100),
            (std::vector<double>{0, 0.25, 0.5, 0.75, 1, 1.5, 2, 2.5, 3, 3.5, 4}));
  PhaseSpec long_;
  long_.steps = 25;
  long_.dt = 1;
  // Stride 3 (25 steps, at most 10): ends 3, 6, ..., 24 and the phase end 25.
  EXPECT_EQ(checkedTimes({long_}, 10),
            (std::vector<double>{0, 2.5, 3, 5.5, 6, 8.5, 9, 11.5, 12, 14.5, 15, 17.5, 18, 20.5, 21,
                                 23.5, 24, 24.5, 25}));
}

}  // namespace
}  // namespace cc::test
