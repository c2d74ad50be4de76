// Contact in whole runs (issue 4): the Coulomb limit reached in full sliding, the assembled exact
// tangent against finite differences of the assembled residual for each contact kind, and the
// convergence of Newton's method with the exact tangent, the paper's parts and the main parts.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "deck_runner.hpp"

namespace cc::test {
namespace {

const std::string kSourceDir = COVCONTACT_SOURCE_DIR;
const std::string kDeckDir = kSourceDir + "/input/verification/contact/";

// An elastic block on an elastic base, small enough to finite-difference the whole system.
// `contact` is the contact line; the block top is pressed (phase 1) and dragged (phase 2).
std::string slidingBlockDeck(const std::string& contact, double drag, int dragSteps) {
  return R"deck(
mesh "../../../meshes/block_on_base.geo" nx=4 ny=2 nz=1 nbx=5 nby=1 blockLength=2 blockHeight=1 baseLength=2.5 baseHeight=0.5 thickness=0.5
material elastic svk E=2.1e4 nu=0.3
elements block hex8 material=elastic
elements base hex8 material=elastic
fix base_bottom all
fix block_front uz
fix block_back uz
fix base_front uz
fix base_back uz
prescribe block_top uy "-4e-3*min(t,1)" ux ")deck" +
         std::to_string(drag) + R"deck(*max(t-1,0)"
)deck" + contact +
         R"deck(
solve
  steps 1 dt=1
  steps )deck" +
         std::to_string(dragSteps) +
         R"deck( dt=1
end
)deck";
}

DeckRun runText(const std::string& text) {
  return runDeckText(text, kDeckDir + "inline.deck");
}

// Central differences of the assembled internal force at displacement u (3N) against the
// assembled K_ff, both at time t with the model's committed history.
double assembledTangentError(Model& model, const Eigen::VectorXd& u, double time,
                             double previousTime) {
  const Eigen::Matrix3Xd& X = model.referenceCoordinates();
  const Eigen::Index numNodes = X.cols();
  const Eigen::Matrix3Xd previous = X;  // only used by contributions for history; fixed here
  auto assemble = [&](const Eigen::VectorXd& displacement, Eigen::VectorXd& force,
                      SystemMatrices* tangent) {
    const Eigen::Matrix3Xd current =
        X + Eigen::Map<const Eigen::Matrix3Xd>(displacement.data(), 3, numNodes);
    AssemblyState state{time, previousTime, &X, &current, &previous};
    model.assemble(state, force, tangent);
  };
  Eigen::VectorXd force;
  SystemMatrices K;
  assemble(u, force, &K);
  const Eigen::MatrixXd analytic(K.free);
  const DofMap& dofs = model.dofMap();
  // Step: truncation h^2 |f'''| ~ 1e-10 relative, round-off eps |f| / h ~ 1e-9 relative.
  const double h = 1e-7;
  Eigen::MatrixXd numeric(dofs.numFree(), dofs.numFree());
  Eigen::VectorXd plusForce, minusForce;
  for (int column = 0; column < dofs.numFree(); ++column) {
    Eigen::VectorXd plus = u, minus = u;
    plus[dofs.freeDofs()[column]] += h;
    minus[dofs.freeDofs()[column]] -= h;
    assemble(plus, plusForce, nullptr);
    assemble(minus, minusForce, nullptr);
    for (int row = 0; row < dofs.numFree(); ++row) {
      const int dof = dofs.freeDofs()[row];
      numeric(row, column) = (plusForce[dof] - minusForce[dof]) / (2 * h);
    }
  }
  assemble(u, force, nullptr);  // leave the trial state at u
  return (analytic - numeric).norm() / numeric.norm();
}

// After two converged drag steps, perturb towards the next step (more drag, more press) and
// compare the assembled exact tangent with finite differences: every contact point is then in
// contact, most of them sliding, with a traction history.
void expectExactAssembledTangent(const std::string& contact) {
  DeckRun run = runText(slidingBlockDeck(contact, 5e-3, 2));
  ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed);
  const RecordedStep& last = run.steps.back();
  Eigen::VectorXd u =
      Eigen::Map<const Eigen::VectorXd>(last.displacement.data(), last.displacement.size());
  const Eigen::Matrix3Xd& X = run.model->referenceCoordinates();
  for (int node : run.model->mesh().nodeSets.at("block").nodes) {
    u[3 * node] += 1e-3 * (1 + X(1, node));
    u[3 * node + 1] -= 2e-4;
  }
  const auto& pair = last.contact.front();
  int sliding = 0;
  for (int i = 0; i < pair.state.size(); ++i) sliding += pair.state[i] == 2;
  EXPECT_GT(sliding, 0);
  EXPECT_LT(assembledTangentError(*run.model, u, last.time + 1, last.time), 1e-6);
}

TEST(ContactRuns, AssembledExactTangentMatchesFiniteDifferencesSts) {
  expectExactAssembledTangent(
      "contact sts master=block_bottom slave=base_top eps_n=2e5 eps_t=2e5 mu=0.3 tangent=exact");
}

TEST(ContactRuns, AssembledExactTangentMatchesFiniteDifferencesNts) {
  expectExactAssembledTangent(
      "contact nts master=block_bottom slave=base_top eps_n=2e5 eps_t=2e5 mu=0.3 tangent=exact");
}

TEST(ContactRuns, AssembledExactTangentMatchesFiniteDifferencesStas) {
  // The base is replaced by a rigid cylinder of large radius under the block.
  const std::string contact =
      "rigid floor cylinder origin=(1,-50,0) axis=(0,0,1) radius=50\n"
      "contact stas master=block_bottom slave=floor eps_n=2e5 eps_t=2e5 mu=0.3 tangent=exact";
  expectExactAssembledTangent(contact);
}

// A block pressed onto a base whose nodes are all fixed, then dragged until every contact point
// slides: |T| = mu |N| at every point along the flat master, so Fx / Fy = mu.
TEST(ContactRuns, FullSlidingReachesCoulombLimit) {
  for (const char* kind : {"sts", "nts"}) {
    SCOPED_TRACE(kind);
    std::string deck = "block_on_fixed_base.deck";
    DeckRun run = [&] {
      if (std::string(kind) == "sts") return runDeckFile(kDeckDir + deck);
      std::ifstream in(kDeckDir + deck);
      std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      return runText(std::regex_replace(text, std::regex("contact sts"), "contact nts"));
    }();
    ASSERT_EQ(run.summary.outcome, RunSummary::Outcome::Completed);
    const RecordedStep& last = run.steps.back();
    const ContactPairRecord& pair = last.pair("interface");
    for (int i = 0; i < pair.state.size(); ++i) {
      if (pair.gap[i] < 0) {
        EXPECT_EQ(pair.state[i], 2) << "point " << i << " not sliding";
      }
    }
    const Eigen::Vector3d top = last.setReaction("block_top");
    EXPECT_NEAR(std::abs(top.x() / top.y()), 0.3, 1e-6);
    EXPECT_NEAR(std::abs(pair.totalForce.x() / pair.totalForce.y()), 0.3, 1e-6);
  }
}

int iterationsInSlidingSteps(const DeckRun& run) {
  int total = 0;
  for (std::size_t k = 2; k < run.steps.size(); ++k) total += run.steps[k].iterations;
  return total;
}

// Full sliding in large steps (the paper's problem type b): the exact tangent converges
// quadratically, r_{k+1} <= C r_k^2 with C of order one, and needs fewer iterations than the
// paper's full tangent, which needs fewer than the main parts alone.
TEST(ContactRuns, ExactTangentConvergesQuadraticallyInSliding) {
  const std::string base =
      "contact sts master=block_bottom slave=base_top eps_n=2.1e5 eps_t=2.1e5 mu=0.3 tangent=";
  DeckRun exact = runText(slidingBlockDeck(base + "exact", 12e-3, 6));
  DeckRun full = runText(slidingBlockDeck(base + "full", 12e-3, 6));
  DeckRun main = runText(slidingBlockDeck(base + "main", 12e-3, 6));
  for (const DeckRun* run : {&exact, &full, &main}) {
    ASSERT_EQ(run->summary.outcome, RunSummary::Outcome::Completed);
  }
  for (std::size_t k = 2; k < exact.steps.size(); ++k) {
    const auto rows = exact.iterationsOf(exact.steps[k].step);
    ASSERT_GE(rows.size(), 3u);
    // The last two ratios r_{k+1} / r_k^2 (relative residuals) stay of order one.
    for (std::size_t i = rows.size() - 2; i + 1 < rows.size(); ++i) {
      const double ratio = rows[i + 1].relativeResidual / std::pow(rows[i].relativeResidual, 2);
      EXPECT_LT(ratio, 10.0) << "step " << exact.steps[k].step << " iteration "
                             << rows[i].iteration;
    }
  }
  EXPECT_LT(iterationsInSlidingSteps(exact), iterationsInSlidingSteps(full));
  EXPECT_LT(iterationsInSlidingSteps(full), iterationsInSlidingSteps(main));
}

}  // namespace
}  // namespace cc::test
