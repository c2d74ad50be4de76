// The PETSc backend on several processes (issues 13 and 17), run under `mpirun -np 2` and
// `-np 3`: each process passes its share of a spring lattice (the springs of the nodes it owns:
// in the pattern of its own springs and of its own rows complete, as NonlinearProblem's shares
// are, or in the whole pattern with the other springs as zeros), and every process must
// receive the solution of the whole system, against CHOLMOD / UMFPACK on one process: MUMPS
// to round-off, GMRES + BoomerAMG / GAMG within cond(K) times their tolerance.
// A share that gains a nonzero in a row of another process only after the pattern was analyzed,
// in rows not coupled to its own (a contact item with no node there), must still count.
// The mesh partition repeats exactly: with PT-Scotch it changed from call to call, and with it
// every iteration count of an AMG-preconditioned run. solver=auto's GAMG probation ends in the
// same solve, with the same notes, on every process.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "parallel/process_group.hpp"
#include "petsc_environment.hpp"
#include "solver/petsc_loader.hpp"
#include "solver/tangent_solver.hpp"
#include "spring_lattice.hpp"

namespace cc {
namespace {

using test::Lattice;
using test::lattice;
using test::latticeNode;
using test::LatticeOptions;
using test::relativeError;

constexpr int kSide = 6;  // 6 x 6 x 6 nodes, 540 equations
constexpr double kKrylovTolerance = 1e-9;

// Slabs of x: process p owns the nodes with i * processes / side == p.
std::vector<int> slabOwners(int processes, int side = kSide) {
  std::vector<int> owner(static_cast<std::size_t>(side * side * side));
  for (int k = 0; k < side; ++k)
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) owner[latticeNode(side, i, j, k)] = i * processes / side;
  return owner;
}

// A spring between two corners of the last process, (n-1, 0, n-1) and (n-1, n-1, n-1), that
// process 0 evaluates (like a contact item whose nodes are all elsewhere): no other spring
// couples its rows to process 0.
const std::pair<int, int> kFarSpring{latticeNode(kSide, kSide - 1, 0, kSide - 1),
                                     latticeNode(kSide, kSide - 1, kSide - 1, kSide - 1)};

// The whole system (owner < 0) or the share of process `owner`; the far spring weighs
// `farWeight`.
Lattice latticeSystem(int owner, double skew, double farWeight) {
  const std::vector<int> nodeOwner = slabOwners(processGroup().size());
  LatticeOptions options;
  options.skew = skew;
  options.extraSprings = {kFarSpring};
  options.weight = [&nodeOwner, owner, farWeight](int a, int b) {
    const bool far = std::pair{a, b} == kFarSpring;
    const int springOwner = far ? 0 : nodeOwner[a];
    return owner < 0 || springOwner == owner ? (far ? farWeight : 1.0) : 0.0;
  };
  Lattice result = lattice(kSide, options);
  if (owner >= 0) result.layout.nodeOwner = nodeOwner;
  return result;
}

Eigen::VectorXd referenceSolution(const SystemMatrices& whole, const Eigen::VectorXd& rhs) {
  TangentSolver direct(whole.symmetric ? LinearSolverSpec::Method::Cholmod
                                       : LinearSolverSpec::Method::Umfpack);
  direct.factorize(whole);
  return direct.solve(rhs);
}

// What the solution of `method` may miss the reference by, given cond(K).
double allowedError(PetscMethod method, double cond) {
  return method == PetscMethod::Mumps ? cond * 1e3 * 2.2e-16 : cond * kKrylovTolerance;
}

std::unique_ptr<LinearSolver> distributedSolver(PetscMethod method, const SystemLayout& layout) {
  auto solver = makePetscSolver(method);
  solver->setLayout(layout);
  solver->setRelativeTolerance(kKrylovTolerance);
  return solver;
}

TEST(DistributedPetsc, TheSharesOfAllProcessesSolveTheWholeSystem) {
  const int rank = processGroup().rank();
  for (const auto& [skew, ownSpringsOnly] : {std::pair{0.0, true}, {0.3, true}, {0.3, false}}) {
    const Lattice whole = latticeSystem(-1, skew, 1.0);
    Lattice share = latticeSystem(rank, skew, 1.0);
    if (ownSpringsOnly) {
      // The other processes' springs stay (as zeros) in this process's rows only.
      const SystemLayout& layout = share.layout;
      share.system.free.prune([&layout, rank](int row, int, double value) {
        const int node = layout.freeDofs[static_cast<std::size_t>(row)] / 3;
        return value != 0 || layout.nodeOwner[static_cast<std::size_t>(node)] == rank;
      });
    }
    const Eigen::VectorXd rhs = test::rightHandSide(whole.system.free.rows());
    const Eigen::VectorXd reference = referenceSolution(whole.system, rhs);
    const double cond = test::conditionNumber(whole.system.free);
    for (PetscMethod method : {PetscMethod::Mumps, PetscMethod::BoomerAmg, PetscMethod::Gamg}) {
      auto solver = distributedSolver(method, share.layout);
      solver->analyzePattern(share.system.free);
      solver->factorize(share.system.free);
      EXPECT_LE(relativeError(solver->solve(rhs), reference), allowedError(method, cond))
          << solver->name() << ", skew " << skew << (ownSpringsOnly ? ", own springs" : "")
          << ", rank " << rank;
    }
  }
}

TEST(DistributedPetsc, ANonzeroThatAppearsAfterTheAnalysisInARowOfAnotherProcessCounts) {
  const int rank = processGroup().rank();
  const Lattice share0 = latticeSystem(rank, 0.3, 0.0), share1 = latticeSystem(rank, 0.3, 1.0);
  const Lattice whole0 = latticeSystem(-1, 0.3, 0.0), whole1 = latticeSystem(-1, 0.3, 1.0);
  const Eigen::VectorXd rhs = test::rightHandSide(whole0.system.free.rows());
  const double cond0 = test::conditionNumber(whole0.system.free);
  const double cond1 = test::conditionNumber(whole1.system.free);
  for (PetscMethod method : {PetscMethod::Mumps, PetscMethod::BoomerAmg}) {
    auto solver = distributedSolver(method, share0.layout);
    solver->analyzePattern(share0.system.free);
    solver->factorize(share0.system.free);
    EXPECT_LE(relativeError(solver->solve(rhs), referenceSolution(whole0.system, rhs)),
              allowedError(method, cond0))
        << solver->name() << ", rank " << rank << ", far spring 0";
    // The same pattern, no new analysis; process 0's share now adds to the far corners' rows.
    solver->factorize(share1.system.free);
    EXPECT_LE(relativeError(solver->solve(rhs), referenceSolution(whole1.system, rhs)),
              allowedError(method, cond1))
        << solver->name() << ", rank " << rank << ", far spring 1";
  }
}

// The node graph of an n x n x n lattice of hexahedra (each node coupled to its 26 neighbours).
std::pair<std::vector<int>, std::vector<int>> hexLatticeGraph(int n) {
  std::vector<int> offsets{0}, adjacency;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const int a = i + di, b = j + dj, c = k + dk;
              if ((di || dj || dk) && a >= 0 && a < n && b >= 0 && b < n && c >= 0 && c < n)
                adjacency.push_back(latticeNode(n, a, b, c));
            }
        offsets.push_back(static_cast<int>(adjacency.size()));
      }
  return {offsets, adjacency};
}

TEST(DistributedPetsc, TheMeshPartitionIsBalancedAndTheSameInEveryCall) {
  constexpr int kGraphSide = 24;  // 13 824 vertices
  const auto [offsets, adjacency] = hexLatticeGraph(kGraphSide);
  const int parts = processGroup().size();
  const std::vector<int> first = processGroup().partition(offsets, adjacency);
  ASSERT_EQ(first.size(), offsets.size() - 1);
  // Balanced to Scotch's 1 % (plus one vertex): every part within it of the mean.
  std::vector<double> count(static_cast<std::size_t>(parts), 0.0);
  for (int owner : first) {
    ASSERT_GE(owner, 0);
    ASSERT_LT(owner, parts);
    ++count[static_cast<std::size_t>(owner)];
  }
  const double mean = static_cast<double>(first.size()) / parts;
  for (double c : count) EXPECT_LE(std::abs(c - mean), 0.01 * mean + 1);
  // Few cut edges: a cut by a plane of the lattice crosses 2 (3n - 2)^2 adjacency entries, and
  // parts - 1 planes cut it into `parts` slabs; a partition that ignored the graph (every k-th
  // vertex, say) would cut most of them.
  int cut = 0;
  for (std::size_t v = 0; v + 1 < offsets.size(); ++v)
    for (int k = offsets[v]; k < offsets[v + 1]; ++k)
      cut += first[v] != first[static_cast<std::size_t>(adjacency[static_cast<std::size_t>(k)])];
  const int planeCut = 2 * (3 * kGraphSide - 2) * (3 * kGraphSide - 2);
  EXPECT_LE(cut, 1.5 * (parts - 1) * planeCut);
  // The same partition on every process: the sum over the processes is size() times this one.
  std::vector<double> owners(first.begin(), first.end()), summed = owners;
  processGroup().sum(summed.data(), summed.size());
  for (std::size_t v = 0; v < owners.size(); ++v) ASSERT_EQ(summed[v], parts * owners[v]);
  for (int call = 1; call < 6; ++call)
    EXPECT_EQ(processGroup().partition(offsets, adjacency), first) << "call " << call;
}

// solver=auto on several processes (tangent_solver.hpp, AutoPreconditionerRule) starts with
// GAMG and replaces it by BoomerAMG when a new hierarchy misses its allowance of Krylov
// iterations. The decision reads PETSc's global iteration count, so every process must switch
// in the same solve and say the same. The rule's threshold moved from 250 000 to 0 equations so
// that a lattice of 50 700 equations (above kIterativeBreakEven) shows it.
struct AutoOnAShare {
  static constexpr int kAutoSide = 26;
  Lattice whole = lattice(kAutoSide);
  Eigen::VectorXd rhs = test::rightHandSide(whole.system.free.rows());
  TangentSolver automatic{LinearSolverSpec::Method::Auto};
  std::vector<std::string> notes;

  explicit AutoOnAShare(double slowestRate) {
    const int rank = processGroup().rank();
    const std::vector<int> owner = slabOwners(processGroup().size(), kAutoSide);
    LatticeOptions options;
    options.weight = [&owner, rank](int a, int) { return owner[a] == rank ? 1.0 : 0.0; };
    share = lattice(kAutoSide, options);
    share.layout.nodeOwner = owner;
    automatic.setNotifier([this](const std::string& line) { notes.push_back(line); });
    AutoPreconditionerRule rule;
    rule.gamgFrom = 0;
    rule.gamgSlowestRate = slowestRate;
    automatic.setAutoPreconditionerRule(rule);
    automatic.setLayout(share.layout);
    automatic.setForcing(1e-8);
    automatic.factorize(share.system);
  }
  double residual(const Eigen::VectorXd& x) const {
    return (whole.system.free * x - rhs).norm() / rhs.norm();
  }
  Lattice share;
};

// Whether every process holds the same lines (a hash of each, summed over the processes).
bool sameOnEveryProcess(const std::vector<std::string>& lines) {
  std::vector<double> hashes{static_cast<double>(lines.size())};
  for (const std::string& line : lines) {
    hashes.push_back(static_cast<double>(std::hash<std::string>{}(line) % (1ull << 40)));
  }
  std::vector<double> summed = hashes;
  const int processes = processGroup().size();
  // Every process takes the same branch (a process returning alone would leave the others
  // waiting in sum()).
  const int count = static_cast<int>(lines.size());
  if (processGroup().maximum(count) != -processGroup().maximum(-count)) return false;
  processGroup().sum(summed.data(), summed.size());
  for (std::size_t k = 0; k < hashes.size(); ++k) {
    if (summed[k] != processes * hashes[k]) return false;
  }
  return true;
}

TEST(DistributedPetsc, AutoKeepsGamgOnEveryProcessWhileItConvergesFastEnough) {
  AutoOnAShare run(kGamgSlowestRate);
  EXPECT_EQ(run.automatic.activeBackend(), "GMRES+GAMG");
  EXPECT_NE(run.automatic.choice().find("on several processes"), std::string::npos)
      << run.automatic.choice();
  EXPECT_LE(run.residual(run.automatic.solve(run.rhs)), 1e-8);
  run.automatic.factorize(run.share.system);  // a kept hierarchy, held to the same allowance
  EXPECT_LE(run.residual(run.automatic.solve(run.rhs)), 1e-8);
  EXPECT_EQ(run.automatic.activeBackend(), "GMRES+GAMG");
  EXPECT_EQ(run.automatic.statistics().reusedPreconditioners, 1);
  EXPECT_EQ(run.notes.size(), 1u) << run.notes.front();  // the choice only
  EXPECT_TRUE(sameOnEveryProcess(run.notes));
}

TEST(DistributedPetsc, AutoReplacesGamgWithBoomerAmgInTheSameSolveOnEveryProcess) {
  // 5 decades per iteration: 8 decades allow 2 GAMG iterations, too few.
  AutoOnAShare run(5.0);
  const Eigen::VectorXd x = run.automatic.solve(run.rhs);
  EXPECT_LE(run.residual(x), 1e-8);
  EXPECT_EQ(run.automatic.activeBackend(), "GMRES+BoomerAMG");
  ASSERT_EQ(run.notes.size(), 3u);
  EXPECT_NE(run.notes[1].find("a new GAMG hierarchy missed its allowance of 2 iterations"),
            std::string::npos)
      << run.notes[1];
  EXPECT_NE(run.notes[2].find("; GMRES+BoomerAMG from Krylov solve 1 on, GAMG too slow"),
            std::string::npos)
      << run.notes[2];
  EXPECT_TRUE(sameOnEveryProcess(run.notes));
  // The processes hold the same solution (PETSc gathers it), and MUMPS was not needed.
  std::vector<double> summed(x.data(), x.data() + x.size());
  processGroup().sum(summed.data(), summed.size());
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    ASSERT_EQ(summed[static_cast<std::size_t>(k)], processGroup().size() * x[k]) << "entry " << k;
  }
  EXPECT_EQ(run.automatic.statistics().krylovFallbacks, 0);
  // BoomerAMG stays for the next tangent, on every process, without a word.
  run.automatic.factorize(run.share.system);
  EXPECT_LE(run.residual(run.automatic.solve(run.rhs)), 1e-8);
  EXPECT_EQ(run.automatic.activeBackend(), "GMRES+BoomerAMG");
  EXPECT_EQ(run.notes.size(), 3u);
}

TEST(DistributedPetsc, RunsOnSeveralProcesses) {
  EXPECT_GT(processGroup().size(), 1);
}

}  // namespace
}  // namespace cc
