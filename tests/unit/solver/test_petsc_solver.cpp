// PETSc backend (issue 13) against the direct solvers on assembled 3-dof-per-node systems: MUMPS
// and SuperLU_dist to round-off, GMRES + BoomerAMG / GAMG to the accuracy their tolerance
// guarantees (||x - x*|| / ||x*|| <= cond(K) * rtol for a true relative residual rtol), the
// Krylov -> direct fallback, singular systems, and the `solver=` choice of TangentSolver.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "petsc_environment.hpp"
#include "solver/linear_solver.hpp"
#include "solver/petsc_loader.hpp"
#include "solver/tangent_solver.hpp"
#include "spring_lattice.hpp"

namespace cc {
namespace {

using test::Lattice;
using test::lattice;

using test::conditionNumber;
using test::directSolution;
using test::relativeError;
using test::rightHandSide;

TEST(PetscSolver, DirectBackendsMatchCholmodToRoundoff) {
  const Lattice model = lattice(5);
  const Eigen::VectorXd rhs = rightHandSide(model.system.free.rows());
  const Eigen::VectorXd reference = directSolution(model.system, rhs);
  // Backward-stable LU: error <= cond * (a modest multiple of) machine epsilon.
  const double bound = conditionNumber(model.system.free) * 1e3 * 2.2e-16;
  for (PetscMethod method : {PetscMethod::Mumps, PetscMethod::SuperluDist}) {
    auto solver = makePetscSolver(method);
    EXPECT_FALSE(solver->iterative());
    solver->analyzePattern(model.system.free);
    solver->factorize(model.system.free);
    EXPECT_LE(relativeError(solver->solve(rhs), reference), bound) << solver->name();
  }
}

TEST(PetscSolver, KrylovBackendsReachTheirToleranceOnSymmetricAndUnsymmetricSystems) {
  for (double skew : {0.0, 0.3}) {
    const Lattice model = lattice(6, skew);
    const Eigen::VectorXd rhs = rightHandSide(model.system.free.rows());
    const Eigen::VectorXd reference = directSolution(model.system, rhs);
    const double rtol = 1e-9;
    const double cond = conditionNumber(model.system.free);
    for (PetscMethod method : {PetscMethod::BoomerAmg, PetscMethod::Gamg}) {
      auto solver = makePetscSolver(method);
      EXPECT_TRUE(solver->iterative());
      solver->setLayout(model.layout);  // node blocks and rigid-body modes
      solver->setRelativeTolerance(rtol);
      solver->analyzePattern(model.system.free);
      solver->factorize(model.system.free);
      const Eigen::VectorXd x = solver->solve(rhs);
      const double residual = (model.system.free * x - rhs).norm() / rhs.norm();
      EXPECT_LE(residual, rtol) << solver->name() << " skew " << skew;
      EXPECT_LE(relativeError(x, reference), cond * rtol) << solver->name() << " skew " << skew;
      EXPECT_GT(solver->lastSolve().iterations, 0);
      EXPECT_LT(solver->lastSolve().iterations, 100)
          << solver->name() << " skew " << skew << ": " << solver->lastSolve().reason;
    }
  }
}

// BoomerAMG's nodal coarsening and GAMG's aggregation of the rigid-body modes work on the
// matrix's block size: with the mesh layout the iterative backends must solve a matrix of 3-row
// node blocks (one process lost it to the preallocation until the 28th session), the direct
// ones and a system without layout a plain one.
TEST(PetscSolver, IterativeBackendsSolveTheNodeBlocksOfTheLayout) {
  const Lattice model = lattice(4);
  for (PetscMethod method : {PetscMethod::BoomerAmg, PetscMethod::Gamg, PetscMethod::Mumps}) {
    for (bool withLayout : {true, false}) {
      auto solver = makePetscSolver(method);
      if (withLayout) solver->setLayout(model.layout);
      solver->analyzePattern(model.system.free);
      solver->factorize(model.system.free);
      const int expected = withLayout && solver->iterative() ? 3 : 1;
      EXPECT_EQ(solver->matrixBlockSize(), expected)
          << solver->name() << (withLayout ? " with" : " without") << " layout";
    }
  }
}

TEST(PetscSolver, RepeatedFactorizationsOfOnePatternReuseTheAnalysis) {
  Lattice model = lattice(4);
  const Eigen::VectorXd rhs = rightHandSide(model.system.free.rows());
  TangentSolver solver(LinearSolverSpec::Method::Mumps);
  for (double scale : {1.0, 2.0, 4.0}) {
    SystemMatrices scaled = model.system;
    scaled.free *= scale;
    solver.factorize(scaled);
    const Eigen::VectorXd x = solver.solve(rhs);
    EXPECT_LE(relativeError(scale * x, directSolution(model.system, rhs)), 1e-10);
  }
  EXPECT_EQ(solver.statistics().analyses, 1);
  EXPECT_EQ(solver.statistics().factorizations, 3);
  EXPECT_EQ(solver.activeBackend(), "MUMPS");
}

// The lagged AMG hierarchy (petsc_solver.cpp, kLaggedRateRatio): a slightly changed matrix is
// solved with the last hierarchy, to the tolerance of the new matrix; a stalled solve makes the
// next factorization rebuild it.
TEST(PetscSolver, GamgKeepsItsHierarchyWhileItConvergesAndRebuildsAfterAStall) {
  const Lattice model = lattice(6, 0.3);
  const Eigen::VectorXd rhs = rightHandSide(model.system.free.rows());
  const double rtol = 1e-9;
  auto solver = makePetscSolver(PetscMethod::Gamg);
  solver->setLayout(model.layout);
  solver->setRelativeTolerance(rtol);
  solver->analyzePattern(model.system.free);
  solver->factorize(model.system.free);
  solver->solve(rhs);
  EXPECT_EQ(solver->statistics().reusedPreconditioners, 0);
  const SparseMatrix changed = 1.02 * model.system.free;
  solver->factorize(changed);
  EXPECT_EQ(solver->statistics().reusedPreconditioners, 1);
  const Eigen::VectorXd x = solver->solve(rhs);
  // GMRES works on the new matrix: its own residual, not the old one's, meets the tolerance.
  EXPECT_LE((changed * x - rhs).norm() / rhs.norm(), rtol);
  EXPECT_GT((model.system.free * x - rhs).norm() / rhs.norm(), 1e-3);
  solver->setIterationLimit(1);  // one GMRES iteration cannot reach 1e-9: a stall
  solver->factorize(model.system.free);
  EXPECT_EQ(solver->statistics().reusedPreconditioners, 2);
  EXPECT_THROW(solver->solve(rhs), KrylovFailure);
  solver->setIterationLimit(400);
  solver->factorize(model.system.free);
  EXPECT_EQ(solver->statistics().reusedPreconditioners, 2);  // rebuilt
  const Eigen::VectorXd y = solver->solve(rhs);
  EXPECT_LE((model.system.free * y - rhs).norm() / rhs.norm(), rtol);
}

TEST(PetscSolver, StalledKrylovSolveFallsBackToTheDirectSolverAndSaysSo) {
  const Lattice model = lattice(5);
  const Eigen::VectorXd rhs = rightHandSide(model.system.free.rows());
  TangentSolver solver(LinearSolverSpec::Method::Amg);
  std::vector<std::string> notes;
  solver.setNotifier([&](const std::string& line) { notes.push_back(line); });
  solver.setLayout(model.layout);
  // Two GMRES iterations cannot reach 1e-10: the solve stalls.
  solver.setForcing(1e-10);
  solver.setKrylovIterationLimit(2);
  solver.factorize(model.system);
  EXPECT_TRUE(solver.iterative());
  const Eigen::VectorXd x = solver.solve(rhs);
  EXPECT_LE(relativeError(x, directSolution(model.system, rhs)),
            conditionNumber(model.system.free) * 1e3 * 2.2e-16);
  EXPECT_EQ(solver.statistics().krylovFallbacks, 1);
  EXPECT_EQ(solver.activeBackend(), "CHOLMOD");
  ASSERT_EQ(notes.size(), 2u) << solver.activeBackend();
  EXPECT_NE(notes[0].find("linear solver: amg -> GMRES+BoomerAMG"), std::string::npos) << notes[0];
  EXPECT_NE(notes[1].find("solving this iteration with CHOLMOD/UMFPACK"), std::string::npos)
      << notes[1];
}

TEST(PetscSolver, AStopRequestEndsAKrylovSolveAtTheNextIteration) {
  const Lattice model = lattice(6, 0.3);
  const Eigen::VectorXd rhs = rightHandSide(model.system.free.rows());
  const double rtol = 1e-12;  // far more than three iterations for either preconditioner
  for (const PetscMethod method : {PetscMethod::BoomerAmg, PetscMethod::Gamg}) {
    auto solver = makePetscSolver(method);
    solver->setLayout(model.layout);
    solver->setRelativeTolerance(rtol);
    int polls = 0;
    solver->setStopPoll([&polls] { return ++polls == 3; });
    solver->analyzePattern(model.system.free);
    solver->factorize(model.system.free);
    EXPECT_THROW(solver->solve(rhs), SolveInterrupted) << solver->name();
    // Polled before the first iteration and after each: the third poll ends the second.
    EXPECT_EQ(solver->lastSolve().iterations, 2) << solver->name();
    // Not a stall: the next solve with the same hierarchy reaches the tolerance.
    solver->factorize(model.system.free);
    EXPECT_EQ(solver->statistics().reusedPreconditioners, 1) << solver->name();
    const Eigen::VectorXd x = solver->solve(rhs);
    EXPECT_LE((model.system.free * x - rhs).norm() / rhs.norm(), rtol) << solver->name();
    EXPECT_GT(polls, 3);
  }
}

TEST(PetscSolver, AStopDuringAKrylovSolveIsPassedOnNotSolvedDirectly) {
  const Lattice model = lattice(5);
  TangentSolver solver(LinearSolverSpec::Method::Amg);
  solver.setStopPoll([] { return true; });
  solver.setLayout(model.layout);
  solver.setForcing(1e-10);
  solver.factorize(model.system);
  EXPECT_THROW(solver.solve(rightHandSide(model.system.free.rows())), SolveInterrupted);
  EXPECT_EQ(solver.statistics().krylovFallbacks, 0);
  EXPECT_EQ(solver.activeBackend(), "GMRES+BoomerAMG");
}

TEST(PetscSolver, SingularSystemIsASingularStepFailure) {
  // A free chain: the constant vector is in the nullspace.
  std::vector<Eigen::Triplet<double>> entries;
  const int n = 12;
  for (int s = 0; s + 1 < n; ++s) {
    entries.emplace_back(s, s, 1.0), entries.emplace_back(s + 1, s + 1, 1.0);
    entries.emplace_back(s, s + 1, -1.0), entries.emplace_back(s + 1, s, -1.0);
  }
  SparseMatrix matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  auto solver = makePetscSolver(PetscMethod::Mumps);
  solver->analyzePattern(matrix);
  try {
    solver->factorize(matrix);
    FAIL() << "MUMPS factorized a singular matrix";
  } catch (const StepFailure& failure) {
    EXPECT_EQ(failure.kind(), FailureKind::SingularSystem);
    EXPECT_NE(std::string(failure.what()).find("MUMPS"), std::string::npos) << failure.what();
  }
}

// The sign of the determinant from MUMPS's factorization (ICNTL 33), which the fold verdict of
// a failing Newton solve takes on models too large for its own factorizations
// (tangent_orientation.hpp): the 1D Laplacian minus s I has the eigenvalues
// 2 - 2 cos(k pi / (n + 1)), k = 1..n, so its determinant has the sign (-1)^(number below s);
// with an unsymmetric perturbation, that of a dense LU's pivots and row permutation. Through
// the backend and through TangentSolver (solver=mumps); SuperLU_dist cannot tell.
TEST(PetscSolver, MumpsTellsTheSignOfTheDeterminant) {
  const double pi = std::acos(-1.0);
  const int n = 40;
  const auto shiftedLaplacian = [&](double shift, double skew) {
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < n; ++i) {
      entries.emplace_back(i, i, 2.0 - shift);
      if (i + 1 < n) {
        entries.emplace_back(i, i + 1, -1.0 + skew * (i % 3 == 0));
        entries.emplace_back(i + 1, i, -1.0);
      }
    }
    SparseMatrix matrix(n, n);
    matrix.setFromTriplets(entries.begin(), entries.end());
    matrix.makeCompressed();
    return matrix;
  };
  const auto denseSign = [](const SparseMatrix& matrix) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu{Eigen::MatrixXd(matrix)};
    double sign = lu.permutationP().determinant();
    for (Eigen::Index i = 0; i < matrix.rows(); ++i) sign *= lu.matrixLU()(i, i) > 0 ? 1 : -1;
    return sign > 0 ? 1 : -1;
  };
  auto mumps = makePetscSolver(PetscMethod::Mumps);
  auto superlu = makePetscSolver(PetscMethod::SuperluDist);
  TangentSolver tangentSolver(LinearSolverSpec::Method::Mumps);
  EXPECT_FALSE(mumps->determinantSign());  // nothing factorized yet
  int version = 0;
  for (const double shift : {0.0, 0.3, 1.1, 2.5, 3.7}) {
    int below = 0;
    for (int k = 1; k <= n; ++k) below += 2 - 2 * std::cos(k * pi / (n + 1)) < shift;
    for (const double skew : {0.0, 0.4}) {
      const SparseMatrix matrix = shiftedLaplacian(shift, skew);
      const int expected = skew == 0 ? (below % 2 ? -1 : 1) : denseSign(matrix);
      mumps->analyzePattern(matrix);
      mumps->factorize(matrix);
      EXPECT_EQ(mumps->determinantSign(), expected) << shift << " " << skew << " " << below;
      SystemMatrices system;
      system.free = matrix;
      system.symmetric = skew == 0;
      system.patternVersion = ++version;
      tangentSolver.factorize(system);
      tangentSolver.solve(Eigen::VectorXd::Ones(n));
      EXPECT_EQ(tangentSolver.determinantSign(), expected) << shift << " " << skew;
      superlu->analyzePattern(matrix);
      superlu->factorize(matrix);
      EXPECT_FALSE(superlu->determinantSign());
    }
  }
  mumps->releaseFactor();
  EXPECT_FALSE(mumps->determinantSign());  // no factor, no sign
}

TEST(PetscSolver, AutoKeepsTheDirectSolversBelowTheBreakEven) {
  const Lattice model = lattice(4);
  TangentSolver solver(LinearSolverSpec::Method::Auto);
  solver.factorize(model.system);
  EXPECT_EQ(solver.activeBackend(), "CHOLMOD");
  EXPECT_EQ(solver.choice(), fmt::format("auto -> CHOLMOD/UMFPACK ({} equations < {})",
                                         model.system.free.rows(), kIterativeBreakEven));
}

// Above the break-even auto solves with GMRES + BoomerAMG on the mesh's node blocks (it chose
// GAMG until the 28th session, which stalled on the bulk die: tangent_solver.hpp).
TEST(PetscSolver, AutoSolvesLargeSystemsWithBoomerAmgOnNodeBlocks) {
  const Lattice model = lattice(26);  // 26^3 nodes, the bottom layer fixed: 50 700 equations
  ASSERT_GE(model.system.free.rows(), kIterativeBreakEven);
  const Eigen::VectorXd rhs = rightHandSide(model.system.free.rows());
  TangentSolver automatic(LinearSolverSpec::Method::Auto);
  automatic.setLayout(model.layout);
  automatic.setForcing(1e-8);
  automatic.factorize(model.system);
  EXPECT_EQ(automatic.activeBackend(), "GMRES+BoomerAMG");
  EXPECT_TRUE(automatic.iterative());
  EXPECT_EQ(automatic.choice().rfind(fmt::format("auto -> GMRES+BoomerAMG ({} equations >= {}",
                                                 model.system.free.rows(), kIterativeBreakEven),
                                     0),
            0u)
      << automatic.choice();
  const Eigen::VectorXd x = automatic.solve(rhs);
  EXPECT_LE((model.system.free * x - rhs).norm() / rhs.norm(), 1e-8);
  EXPECT_EQ(automatic.statistics().krylovFallbacks, 0);
}

// On several processes from kGamgFirstFrom equations auto starts with GAMG (faster there on
// thin models) and holds each new GAMG hierarchy to a convergence rate (the bulk die, where
// GAMG stalls). The rule moved here so that one process and a lattice of 50 k equations show it.
AutoPreconditionerRule gamgFromTheStart(double slowestRate) {
  AutoPreconditionerRule rule;
  rule.gamgFrom = 0;
  rule.gamgNeedsSeveralProcesses = false;
  rule.gamgSlowestRate = slowestRate;
  return rule;
}

// auto with that rule on a lattice of 50 700 equations, forcing 1e-8, its first tangent
// factorized; `notes` collects what the solver says.
struct AutoOnALattice {
  Lattice model = lattice(26);
  Eigen::VectorXd rhs = rightHandSide(model.system.free.rows());
  TangentSolver automatic{LinearSolverSpec::Method::Auto};
  std::vector<std::string> notes;

  explicit AutoOnALattice(double slowestRate) {
    automatic.setNotifier([this](const std::string& line) { notes.push_back(line); });
    automatic.setAutoPreconditionerRule(gamgFromTheStart(slowestRate));
    automatic.setLayout(model.layout);
    automatic.setForcing(1e-8);
    automatic.factorize(model.system);
  }
};

TEST(PetscSolver, AutoKeepsGamgWhileANewHierarchyConvergesFastEnough) {
  AutoOnALattice run(kGamgSlowestRate);
  auto& [model, rhs, automatic, notes] = run;
  EXPECT_EQ(automatic.activeBackend(), "GMRES+GAMG");
  EXPECT_NE(automatic.choice().find("GAMG from 0, BoomerAMG once a new GAMG hierarchy converges "
                                    "slower than 0.07 decades per Krylov iteration"),
            std::string::npos)
      << automatic.choice();
  Eigen::VectorXd x = automatic.solve(rhs);
  EXPECT_LE((model.system.free * x - rhs).norm() / rhs.norm(), 1e-8);
  // Fast enough: 8 decades within 8 / 0.07 = 115 iterations.
  EXPECT_LE(automatic.statistics().krylovIterations, 115);
  // The next tangent keeps the hierarchy and is held to the same allowance, which it meets.
  automatic.factorize(model.system);
  EXPECT_EQ(automatic.statistics().reusedPreconditioners, 1);
  x = automatic.solve(rhs);
  EXPECT_LE((model.system.free * x - rhs).norm() / rhs.norm(), 1e-8);
  EXPECT_EQ(automatic.activeBackend(), "GMRES+GAMG");
  EXPECT_EQ(automatic.statistics().solves, 2);
  EXPECT_EQ(notes.size(), 1u);  // the choice only
}

TEST(PetscSolver, AutoReplacesGamgWithBoomerAmgWhenANewHierarchyConvergesTooSlowly) {
  // 5 decades per iteration: 8 decades allow ceil(8 / 5) = 2 GAMG iterations, too few.
  AutoOnALattice run(5.0);
  auto& [model, rhs, automatic, notes] = run;
  EXPECT_EQ(automatic.activeBackend(), "GMRES+GAMG");
  Eigen::VectorXd x = automatic.solve(rhs);
  EXPECT_LE((model.system.free * x - rhs).norm() / rhs.norm(), 1e-8);
  EXPECT_EQ(automatic.activeBackend(), "GMRES+BoomerAMG");
  ASSERT_EQ(notes.size(), 3u);
  EXPECT_NE(notes[1].find("GMRES+GAMG: DIVERGED_ITS after 2 iterations"), std::string::npos)
      << notes[1];
  EXPECT_NE(notes[1].find("a new GAMG hierarchy missed its allowance of 2 iterations (5 decades "
                          "per iteration); GMRES+BoomerAMG solves this iteration and the rest of "
                          "the run"),
            std::string::npos)
      << notes[1];
  // The choice again, as the results file's summary keeps it.
  EXPECT_EQ(notes[2], "linear solver: " + automatic.choice());
  EXPECT_NE(notes[2].find("; GMRES+BoomerAMG from Krylov solve 1 on, GAMG too slow"),
            std::string::npos)
      << notes[2];
  LinearSolverStatistics statistics = automatic.statistics();
  EXPECT_EQ(statistics.krylovFallbacks, 0);  // no direct solve
  EXPECT_EQ(statistics.solves, 2);           // GAMG's two iterations are counted
  EXPECT_EQ(statistics.factorizations, 2);
  // BoomerAMG stays, at no rate: the next tangent is BoomerAMG's without a word.
  automatic.factorize(model.system);
  x = automatic.solve(rhs);
  EXPECT_LE((model.system.free * x - rhs).norm() / rhs.norm(), 1e-8);
  EXPECT_EQ(automatic.activeBackend(), "GMRES+BoomerAMG");
  EXPECT_EQ(notes.size(), 3u);
}

TEST(PetscSolver, AutoGoesFromAStaleGamgHierarchyToANewOneToBoomerAmgToTheDirectSolver) {
  AutoOnALattice run(kGamgSlowestRate);
  auto& [model, rhs, automatic, notes] = run;
  automatic.solve(rhs);  // builds GAMG's hierarchy and passes
  // Two iterations of any Krylov solve from now on: the kept hierarchy stalls, so does a new
  // one, then BoomerAMG, and CHOLMOD solves.
  automatic.setKrylovIterationLimit(2);
  automatic.factorize(model.system);
  const Eigen::VectorXd x = automatic.solve(rhs);
  EXPECT_LE(relativeError(x, directSolution(model.system, rhs)), 1e-10);
  EXPECT_EQ(automatic.activeBackend(), "CHOLMOD");
  const LinearSolverStatistics statistics = automatic.statistics();
  EXPECT_EQ(statistics.krylovFallbacks, 1);
  EXPECT_EQ(statistics.reusedPreconditioners, 1);  // the stale hierarchy, then a new one
  ASSERT_EQ(notes.size(), 4u);
  EXPECT_NE(notes[1].find("GMRES+GAMG: DIVERGED_ITS after 2 iterations"), std::string::npos)
      << notes[1];
  // GAMG's solves: the first, the stale hierarchy's and the new one's.
  EXPECT_NE(notes[2].find("GMRES+BoomerAMG from Krylov solve 3 on"), std::string::npos) << notes[2];
  EXPECT_NE(notes[3].find("GMRES+BoomerAMG: DIVERGED_ITS after 2 iterations"), std::string::npos)
      << notes[3];
  EXPECT_NE(notes[3].find("solving this iteration with CHOLMOD/MUMPS"), std::string::npos)
      << notes[3];
}

TEST(PetscSolver, AutoFactorizesLargeUnsymmetricSystemsWithMumps) {
  // 17^3 nodes: 13 872 equations, above kUnsymmetricMumpsBreakEven; the skew makes the system
  // unsymmetric like a sliding contact tangent. The solution must be UMFPACK's to round-off.
  const Lattice model = lattice(17, 0.3);
  ASSERT_GE(model.system.free.rows(), kUnsymmetricMumpsBreakEven);
  const SystemMatrices& system = model.system;
  ASSERT_FALSE(system.symmetric);
  const Eigen::VectorXd rhs = rightHandSide(system.free.rows());
  TangentSolver automatic(LinearSolverSpec::Method::Auto);
  automatic.factorize(system);
  EXPECT_EQ(automatic.activeBackend(), "MUMPS");
  EXPECT_EQ(automatic.choice(),
            fmt::format("auto -> CHOLMOD/MUMPS ({} equations < {}; unsymmetric systems to MUMPS "
                        "from {})",
                        system.free.rows(), kIterativeBreakEven, kUnsymmetricMumpsBreakEven));
  TangentSolver umfpack(LinearSolverSpec::Method::Umfpack);
  umfpack.factorize(system);
  EXPECT_EQ(umfpack.activeBackend(), "UMFPACK");
  const Eigen::VectorXd reference = umfpack.solve(rhs);
  EXPECT_LE(relativeError(automatic.solve(rhs), reference), 1e-9);
  // Below the break-even, and symmetric systems at any size, stay with UMFPACK and CHOLMOD.
  const Lattice small = lattice(8, 0.3);
  TangentSolver smallAutomatic(LinearSolverSpec::Method::Auto);
  smallAutomatic.factorize(small.system);
  EXPECT_EQ(smallAutomatic.activeBackend(), "UMFPACK");
  TangentSolver symmetricAutomatic(LinearSolverSpec::Method::Auto);
  const Lattice symmetric = lattice(17);
  symmetricAutomatic.factorize(symmetric.system);
  EXPECT_EQ(symmetricAutomatic.activeBackend(), "CHOLMOD");
}

}  // namespace
}  // namespace cc
