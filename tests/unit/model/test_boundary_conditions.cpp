// Boundary conditions of whole decks (issue 15): the built-in node set `all` (plane strain with
// one line, `fix all uz`) checked against the closed-form St. Venant-Kirchhoff plane-strain
// stretch.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "deck_runner.hpp"

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

}  // namespace
}  // namespace cc::test
