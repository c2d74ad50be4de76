// Assembler: coloring validity, scatter against a dense reference, parallel == serial,
// pattern reuse and rebuild on topology change, failure reporting.
#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <set>

#include "common/stopwatch.hpp"
#include "fem/assembler.hpp"
#include "fem/coloring.hpp"
#include "grid_springs.hpp"

namespace cc {
namespace {

using test::GridSprings;

// Fixes the bottom layer (z = 0) fully and prescribes ux on the top layer.
DofMap gridDofs(const GridSprings& grid, int nz) {
  const Eigen::Matrix3Xd x = grid.referenceMatrix();
  std::vector<bool> constrained(3 * grid.numNodes(), false);
  for (int n = 0; n < grid.numNodes(); ++n) {
    if (x(2, n) == 0) constrained[3 * n] = constrained[3 * n + 1] = constrained[3 * n + 2] = true;
    if (x(2, n) == nz) constrained[3 * n] = true;
  }
  return DofMap(std::vector<bool>(grid.numNodes(), true), constrained);
}

// A deterministic, non-trivial displacement field.
Eigen::Matrix3Xd displaced(const Eigen::Matrix3Xd& reference) {
  Eigen::Matrix3Xd current = reference;
  for (int n = 0; n < reference.cols(); ++n) {
    current.col(n) += 0.01 * Eigen::Vector3d(std::sin(n), std::cos(2.0 * n), std::sin(3.0 * n));
  }
  return current;
}

struct Assembled {
  Eigen::VectorXd force;
  SystemMatrices matrices;
};

Assembled assembleWithThreads(int threads, GridSprings& grid, const DofMap& dofs) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  const Eigen::Matrix3Xd reference = grid.referenceMatrix();
  const Eigen::Matrix3Xd current = displaced(reference);
  AssemblyState state;
  state.reference = &reference;
  state.current = &current;
  state.previous = &reference;
  Assembler assembler(dofs, {&grid});
  assembler.setMinItemsForThreads(1);  // the small grids below must exercise the threads
  EXPECT_EQ(assembler.threads(), threads);
  Assembled result;
  assembler.assemble(state, result.force, &result.matrices);
  omp_set_num_threads(saved);
  return result;
}

TEST(Coloring, NoTwoItemsOfOneColorShareANodeAndEveryItemIsColoredOnce) {
  GridSprings grid(5, 4, 3);
  const ItemColoring coloring = colorItems(grid, grid.numNodes());
  ASSERT_EQ(coloring.items.size(), grid.itemCount());
  // A node of a structured hex grid touches 8 cells, so at least 8 colors are needed.
  EXPECT_GE(coloring.numColors(), 8u);
  std::set<std::size_t> seen;
  for (std::size_t color = 0; color < coloring.numColors(); ++color) {
    std::set<int> nodesOfColor;
    for (std::size_t k = coloring.colorBegin[color]; k < coloring.colorBegin[color + 1]; ++k) {
      EXPECT_TRUE(seen.insert(coloring.items[k]).second);
      for (int node : grid.itemNodes(coloring.items[k])) {
        EXPECT_TRUE(nodesOfColor.insert(node).second)
            << "node " << node << " appears twice in color " << color;
      }
    }
  }
  EXPECT_EQ(seen.size(), grid.itemCount());
}

TEST(Assembler, MatchesDenseReferenceAssembly) {
  const int nz = 4;
  GridSprings grid(5, 4, nz);  // 80 cells: enough to run on several threads
  const DofMap dofs = gridDofs(grid, nz);
  const Assembled result = assembleWithThreads(2, grid, dofs);

  const int size = 3 * grid.numNodes();
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(size, size);
  for (std::size_t item = 0; item < grid.itemCount(); ++item) {
    const Eigen::MatrixXd local = grid.localStiffness(item);
    const auto nodes = grid.itemNodes(item);
    for (int a = 0; a < 8; ++a)
      for (int b = 0; b < 8; ++b)
        dense.block<3, 3>(3 * nodes[a], 3 * nodes[b]) += local.block<3, 3>(3 * a, 3 * b);
  }
  const Eigen::Matrix3Xd reference = grid.referenceMatrix();
  const Eigen::Matrix3Xd difference = displaced(reference) - reference;
  const Eigen::VectorXd expectedForce =
      dense * Eigen::Map<const Eigen::VectorXd>(difference.data(), size);
  EXPECT_LT((result.force - expectedForce).norm(), 1e-13 * expectedForce.norm());

  const Eigen::MatrixXd free = Eigen::MatrixXd(result.matrices.free);
  const Eigen::MatrixXd coupling = Eigen::MatrixXd(result.matrices.coupling);
  ASSERT_EQ(free.rows(), dofs.numFree());
  ASSERT_EQ(coupling.cols(), dofs.numPrescribed());
  double largestError = 0;
  for (int i = 0; i < dofs.numFree(); ++i) {
    for (int j = 0; j < dofs.numFree(); ++j) {
      largestError = std::max(largestError,
                              std::abs(free(i, j) - dense(dofs.freeDofs()[i], dofs.freeDofs()[j])));
    }
    for (int p = 0; p < dofs.numPrescribed(); ++p) {
      largestError =
          std::max(largestError,
                   std::abs(coupling(i, p) - dense(dofs.freeDofs()[i], dofs.prescribedDofs()[p])));
    }
  }
  EXPECT_LT(largestError, 1e-13);
  EXPECT_TRUE(result.matrices.symmetric);
  EXPECT_NE(result.matrices.patternVersion, 0u);
}

TEST(Assembler, ParallelAssemblyEqualsSerialBitForBit) {
  // Colors fix the order in which items add into any entry, whatever the thread count.
  const int nz = 4;
  GridSprings grid(5, 5, nz);  // 100 cells: enough to run on several threads
  const DofMap dofs = gridDofs(grid, nz);
  const Assembled serial = assembleWithThreads(1, grid, dofs);
  const Assembled parallel = assembleWithThreads(2, grid, dofs);
  EXPECT_EQ(serial.force, parallel.force);
  EXPECT_TRUE(serial.matrices.free.isApprox(parallel.matrices.free, 0.0));
  EXPECT_EQ((Eigen::MatrixXd(serial.matrices.free) - Eigen::MatrixXd(parallel.matrices.free))
                .cwiseAbs()
                .maxCoeff(),
            0.0);
  EXPECT_EQ(
      (Eigen::MatrixXd(serial.matrices.coupling) - Eigen::MatrixXd(parallel.matrices.coupling))
          .cwiseAbs()
          .maxCoeff(),
      0.0);
}

// Items given explicitly; tests change them and bump the version like a contact search would.
class ListContribution : public Contribution {
 public:
  std::vector<std::vector<int>> items;
  std::uint64_t version = 1;
  std::set<std::size_t> failing;  // items that report a failure
  std::size_t nanItem = std::numeric_limits<std::size_t>::max();
  std::size_t infiniteTangentItem = std::numeric_limits<std::size_t>::max();
  double tangentScale = 1.0;  // entries of the identity tangent
  bool symmetric = true;

  std::string name() const override { return "list"; }
  std::size_t itemCount() const override { return items.size(); }
  std::span<const int> itemNodes(std::size_t item) const override { return items[item]; }
  std::uint64_t topologyVersion() const override { return version; }
  bool tangentSymmetric() const override { return symmetric; }
  LocalStatus evaluate(std::size_t item, const AssemblyState&, Eigen::VectorXd& force,
                       Eigen::MatrixXd* tangent) override {
    if (failing.count(item)) {
      return LocalStatus::failure(FailureKind::InvertedElement, "det J = -1 at point 3");
    }
    force.setOnes();
    if (item == nanItem) force[0] = std::numeric_limits<double>::quiet_NaN();
    if (tangent) {
      tangent->setIdentity();
      *tangent *= tangentScale;
      if (item == infiniteTangentItem) (*tangent)(1, 4) = -std::numeric_limits<double>::infinity();
    }
    return LocalStatus::success();
  }
};

struct ListFixture {
  Eigen::Matrix3Xd reference = Eigen::Matrix3Xd::Zero(3, 6);
  DofMap dofs{std::vector<bool>(6, true), std::vector<bool>(18, false)};
  ListContribution list;
  AssemblyState state;
  ListFixture() {
    list.items = {{0, 1}, {1, 2}, {3, 4}};
    state.reference = state.current = state.previous = &reference;
  }
};

TEST(Assembler, PatternKeptWhileTopologyUnchangedAndRebuiltWhenItChanges) {
  ListFixture fixture;
  Assembler assembler(fixture.dofs, {&fixture.list});
  Eigen::VectorXd force;
  SystemMatrices matrices;
  for (int k = 0; k < 3; ++k) assembler.assemble(fixture.state, force, &matrices);
  EXPECT_EQ(assembler.timings().patternBuilds, 1);
  EXPECT_EQ(assembler.timings().colorings, 1);
  const std::uint64_t firstVersion = matrices.patternVersion;
  const Eigen::Index firstNonZeros = matrices.free.nonZeros();

  fixture.list.items.push_back({4, 5});
  ++fixture.list.version;
  assembler.assemble(fixture.state, force, &matrices);
  EXPECT_EQ(assembler.timings().patternBuilds, 2);
  EXPECT_EQ(assembler.timings().colorings, 2);
  EXPECT_NE(matrices.patternVersion, firstVersion);
  // Every active node already has its diagonal block; the new item adds blocks (4,5), (5,4).
  EXPECT_EQ(matrices.free.nonZeros(), firstNonZeros + 2 * 9);

  // A new item list with the same node graph keeps the pattern version (no new analysis).
  const std::uint64_t secondVersion = matrices.patternVersion;
  fixture.list.items.push_back({5, 4});
  ++fixture.list.version;
  assembler.assemble(fixture.state, force, &matrices);
  EXPECT_EQ(assembler.timings().patternBuilds, 3);
  EXPECT_EQ(matrices.patternVersion, secondVersion);

  // Residual-only assemblies never build a pattern.
  for (int k = 0; k < 2; ++k) assembler.assemble(fixture.state, force, nullptr);
  EXPECT_EQ(assembler.timings().patternBuilds, 3);
  EXPECT_EQ(assembler.timings().assemblies, 7);
}

// On several processes a process's pattern holds its own items' entries and, in the rows of the
// nodes it owns, every other item's too (as zeros): PETSc takes those rows as they are, and the
// values an item adds to another process's rows go there (parallel/petsc_solver.cpp).
TEST(Assembler, TheRowsOfOwnedNodesHoldTheOtherProcessesItems) {
  ListFixture fixture;  // items {0,1} {1,2} {3,4}
  Assembler assembler(fixture.dofs, {&fixture.list});
  // This process owns nodes 0 and 1 and assembles item {0,1}; {1,2} and {3,4} are another's.
  assembler.setItemFilter(
      [](std::size_t, std::size_t item) { return item == 0 ? ItemRole::Assemble : ItemRole::Skip; },
      {1, 1, 0, 0, 0, 0});
  Eigen::VectorXd force;
  SystemMatrices matrices;
  assembler.assemble(fixture.state, force, &matrices);
  const auto blockPresent = [&matrices](int rowNode, int columnNode) {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        bool found = false;
        const int column = 3 * columnNode + b;
        for (SparseMatrix::InnerIterator it(matrices.free, column); it; ++it)
          found = found || it.row() == 3 * rowNode + a;
        if (!found) return false;
      }
    return true;
  };
  EXPECT_TRUE(blockPresent(0, 1));  // its own item, both ways
  EXPECT_TRUE(blockPresent(1, 0));
  EXPECT_TRUE(blockPresent(1, 2));   // the other's item {1,2} in owned row 1,
  EXPECT_FALSE(blockPresent(2, 1));  // not in row 2, which another process owns
  EXPECT_FALSE(blockPresent(3, 4));  // {3,4} has no owned node
  EXPECT_FALSE(blockPresent(4, 3));
  // The values are its own item's only (identity tangents): node 1's diagonal has item {0,1}'s
  // 1, node 2's diagonal nothing.
  EXPECT_EQ(matrices.free.coeff(3, 3), 1.0);
  EXPECT_EQ(matrices.free.coeff(6, 6), 0.0);
}

TEST(Assembler, ReportsTheFirstFailingItemByContributionName) {
  ListFixture fixture;
  fixture.list.failing = {2, 1};
  Assembler assembler(fixture.dofs, {&fixture.list});
  Eigen::VectorXd force;
  SystemMatrices matrices;
  try {
    assembler.assemble(fixture.state, force, &matrices);
    FAIL() << "expected StepFailure";
  } catch (const StepFailure& failure) {
    EXPECT_EQ(failure.kind(), FailureKind::InvertedElement);
    EXPECT_STREQ(failure.what(), "list item 1: det J = -1 at point 3");
  }
}

TEST(Assembler, NonFiniteLocalForceIsCaughtAndNamed) {
  ListFixture fixture;
  fixture.list.nanItem = 2;
  Assembler assembler(fixture.dofs, {&fixture.list});
  Eigen::VectorXd force;
  try {
    assembler.assemble(fixture.state, force, nullptr);
    FAIL() << "expected StepFailure";
  } catch (const StepFailure& failure) {
    EXPECT_EQ(failure.kind(), FailureKind::NotFinite);
    EXPECT_NE(std::string(failure.what()).find("list item 2"), std::string::npos);
  }
}

TEST(Assembler, InfiniteTangentEntryIsCaughtButHugeFiniteOnesAreNot) {
  ListFixture fixture;
  fixture.list.infiniteTangentItem = 1;
  Assembler assembler(fixture.dofs, {&fixture.list});
  Eigen::VectorXd force;
  SystemMatrices matrices;
  EXPECT_NO_THROW(assembler.assemble(fixture.state, force, nullptr));  // no tangent asked
  try {
    assembler.assemble(fixture.state, force, &matrices);
    FAIL() << "expected StepFailure";
  } catch (const StepFailure& failure) {
    EXPECT_EQ(failure.kind(), FailureKind::NotFinite);
    EXPECT_NE(std::string(failure.what()).find("list item 1"), std::string::npos);
  }
  // Entries whose sum would overflow are finite all the same.
  fixture.list.infiniteTangentItem = std::numeric_limits<std::size_t>::max();
  fixture.list.tangentScale = 0.9 * std::numeric_limits<double>::max();
  EXPECT_NO_THROW(assembler.assemble(fixture.state, force, &matrices));
}

TEST(Assembler, SymmetryFlagIsTheAndOfAllContributions) {
  ListFixture fixture;
  ListContribution second;
  second.items = {{2, 3}};
  second.symmetric = false;
  Assembler assembler(fixture.dofs, {&fixture.list, &second});
  Eigen::VectorXd force;
  SystemMatrices matrices;
  assembler.assemble(fixture.state, force, &matrices);
  EXPECT_FALSE(matrices.symmetric);
  // Node 2 gets 1 from item {1,2} of the first list and 1 from the second contribution.
  EXPECT_EQ(force.segment<3>(6), Eigen::Vector3d::Constant(2.0));
}

// Items of 2 to 5 nodes (like contact items next to elements) scattered over a node range,
// with values depending on the item and the node, so any misplaced add shows.
class MixedItems : public Contribution {
 public:
  explicit MixedItems(int numNodes) {
    for (int item = 0; item < 400; ++item) {
      std::vector<int> nodes;
      const int size = 2 + item % 4;
      for (int k = 0; k < size; ++k) nodes.push_back((item * 7 + k * 13) % numNodes);
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      items_.push_back(nodes);
    }
  }
  std::string name() const override { return "mixed"; }
  std::size_t itemCount() const override { return items_.size(); }
  std::span<const int> itemNodes(std::size_t item) const override { return items_[item]; }
  LocalStatus evaluate(std::size_t item, const AssemblyState&, Eigen::VectorXd& force,
                       Eigen::MatrixXd* tangent) override {
    for (Eigen::Index k = 0; k < force.size(); ++k) force[k] = std::sin(1.0 + item + 0.1 * k);
    if (tangent) {
      for (Eigen::Index i = 0; i < tangent->rows(); ++i)
        for (Eigen::Index j = 0; j < tangent->cols(); ++j)
          (*tangent)(i, j) = std::cos(0.5 * item + i + 0.3 * j);
    }
    return LocalStatus::success();
  }

 private:
  std::vector<std::vector<int>> items_;
};

TEST(Assembler, ItemsOfMixedSizesOnFourThreadsEqualOneThread) {
  const int numNodes = 97;
  std::vector<bool> constrained(3 * numNodes, false);
  for (int dof = 0; dof < 3 * numNodes; dof += 5) constrained[dof] = true;
  const DofMap dofs(std::vector<bool>(numNodes, true), constrained);
  const Eigen::Matrix3Xd reference = Eigen::Matrix3Xd::Zero(3, numNodes);
  AssemblyState state;
  state.reference = state.current = state.previous = &reference;
  MixedItems items(numNodes);
  Assembled runs[2];
  const int saved = omp_get_max_threads();
  for (int run = 0; run < 2; ++run) {
    omp_set_num_threads(run == 0 ? 1 : 4);
    Assembler assembler(dofs, {&items});
    assembler.setMinItemsForThreads(1);
    assembler.assemble(state, runs[run].force, &runs[run].matrices);
  }
  omp_set_num_threads(saved);
  EXPECT_EQ(runs[0].force, runs[1].force);
  EXPECT_EQ(Eigen::MatrixXd(runs[0].matrices.free), Eigen::MatrixXd(runs[1].matrices.free));
  EXPECT_EQ(Eigen::MatrixXd(runs[0].matrices.coupling), Eigen::MatrixXd(runs[1].matrices.coupling));
  // Independent check of one entry: the force on node 0 is the sum over items containing it.
  Eigen::Vector3d expected = Eigen::Vector3d::Zero();
  for (std::size_t item = 0; item < items.itemCount(); ++item) {
    const auto nodes = items.itemNodes(item);
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      if (nodes[k] != 0) continue;
      for (int c = 0; c < 3; ++c) expected[c] += std::sin(1.0 + item + 0.1 * (3 * k + c));
    }
  }
  EXPECT_LT((runs[1].force.head<3>() - expected).norm(), 1e-13);
}

// A bug inside an item evaluation (not a StepFailure) must surface as itself, not terminate.
class ThrowingItems : public ListContribution {
 public:
  LocalStatus evaluate(std::size_t item, const AssemblyState&, Eigen::VectorXd&,
                       Eigen::MatrixXd*) override {
    if (item == 1) throw std::logic_error("bug in item 1");
    return LocalStatus::success();
  }
};

// Grid springs whose items each burn `itemCpuSeconds` of thread CPU time and record whether an
// item ran inside an active parallel region.
class CostlyGridSprings : public GridSprings {
 public:
  CostlyGridSprings(int nx, int ny, int nz, double itemCpuSeconds)
      : GridSprings(nx, ny, nz), itemCpuSeconds_(itemCpuSeconds) {}
  LocalStatus evaluate(std::size_t item, const AssemblyState& state, Eigen::VectorXd& force,
                       Eigen::MatrixXd* tangent) override {
    // No clock reading for a cheap item: one costs 1.3 us in the CI's virtual machines, so two
    // per item made the "cheap" items 8 us, at the threshold (7.7 us for 200 items in 8 colors).
    if (itemCpuSeconds_ > 0) {
      const double start = threadCpuSeconds();
      while (threadCpuSeconds() - start < itemCpuSeconds_) {
      }
    }
    if (omp_in_parallel()) ranInParallel = true;
    return GridSprings::evaluate(item, state, force, tangent);
  }
  std::atomic<bool> ranInParallel = false;

 private:
  double itemCpuSeconds_;
};

// The threshold for threads weighs the item count by the measured cost per item (issue 13):
// 200 items of 100 us (20 ms of work) go parallel once measured, 200 cheap ones do not, and
// neither does the first, unmeasured assembly (counted in items: 200 < 2048).
TEST(Assembler, ExpensiveItemsGoParallelOnceTheirCostIsMeasured) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(2);
  CostlyGridSprings costly(10, 5, 4, 100e-6), cheap(10, 5, 4, 0);
  ASSERT_EQ(costly.itemCount(), 200u);
  for (CostlyGridSprings* grid : {&costly, &cheap}) {
    const DofMap dofs = gridDofs(*grid, 4);
    const Eigen::Matrix3Xd reference = grid->referenceMatrix();
    const Eigen::Matrix3Xd current = displaced(reference);
    AssemblyState state;
    state.reference = &reference;
    state.current = &current;
    state.previous = &reference;
    Assembler assembler(dofs, {grid});
    Assembled first, second;
    assembler.assemble(state, first.force, &first.matrices);
    EXPECT_FALSE(grid->ranInParallel) << "first assembly, item cost " << (grid == &costly);
    assembler.assemble(state, second.force, &second.matrices);
    EXPECT_EQ(grid->ranInParallel, grid == &costly);
    // Serial and parallel evaluation add in the same order (by color): equal bit for bit.
    EXPECT_EQ((second.force - first.force).cwiseAbs().maxCoeff(), 0.0);
  }
  omp_set_num_threads(saved);
}

TEST(Assembler, OtherExceptionsFromItemsAreRethrownAfterTheParallelLoop) {
  ListFixture fixture;
  ThrowingItems items;
  items.items = fixture.list.items;
  Assembler assembler(fixture.dofs, {&items});
  assembler.setMinItemsForThreads(1);
  Eigen::VectorXd force;
  EXPECT_THROW(assembler.assemble(fixture.state, force, nullptr), std::logic_error);
}

}  // namespace
}  // namespace cc
