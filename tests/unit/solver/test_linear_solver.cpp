// Linear solvers: CHOLMOD and UMFPACK against dense references, the CHOLMOD -> UMFPACK fallback
// for symmetric indefinite systems, singular systems, reuse of the symbolic analysis, and reuse
// of a factor as the GMRES preconditioner of later tangents.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <climits>
#include <cmath>
#include <random>

#include "common/errors.hpp"
#include "solver/factor_reuse.hpp"
#include "solver/linear_solver.hpp"
#include "solver/tangent_orientation.hpp"
#include "solver/tangent_solver.hpp"

namespace cc {
namespace {

// 5-point Laplacian on an n x n grid with Dirichlet boundary, minus shift * I, full storage.
SparseMatrix gridLaplacian(int n, double shift) {
  std::vector<Eigen::Triplet<double>> entries;
  auto index = [n](int i, int j) { return i + n * j; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      entries.emplace_back(index(i, j), index(i, j), 4.0 - shift);
      if (i + 1 < n) {
        entries.emplace_back(index(i, j), index(i + 1, j), -1.0);
        entries.emplace_back(index(i + 1, j), index(i, j), -1.0);
      }
      if (j + 1 < n) {
        entries.emplace_back(index(i, j), index(i, j + 1), -1.0);
        entries.emplace_back(index(i, j + 1), index(i, j), -1.0);
      }
    }
  SparseMatrix matrix(n * n, n * n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  return matrix;
}

// Stiffness of a chain of springs with the given stiffnesses and free ends (one rigid mode).
SparseMatrix freeChain(const std::vector<double>& stiffness) {
  const int n = static_cast<int>(stiffness.size()) + 1;
  std::vector<Eigen::Triplet<double>> entries;
  for (int s = 0; s + 1 < n; ++s) {
    entries.emplace_back(s, s, stiffness[s]);
    entries.emplace_back(s + 1, s + 1, stiffness[s]);
    entries.emplace_back(s, s + 1, -stiffness[s]);
    entries.emplace_back(s + 1, s, -stiffness[s]);
  }
  SparseMatrix matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  return matrix;
}

Eigen::VectorXd rightHandSide(Eigen::Index size) {
  Eigen::VectorXd rhs(size);
  for (Eigen::Index k = 0; k < size; ++k) rhs[k] = std::sin(1.0 + static_cast<double>(k));
  return rhs;
}

double relativeResidual(const SparseMatrix& matrix, const Eigen::VectorXd& x,
                        const Eigen::VectorXd& rhs) {
  return (matrix * x - rhs).norm() / rhs.norm();
}

SystemMatrices systemOf(SparseMatrix matrix, bool symmetric, std::uint64_t version) {
  SystemMatrices system;
  system.free = std::move(matrix);
  system.symmetric = symmetric;
  system.patternVersion = version;
  return system;
}

TEST(LinearSolver, CholmodSolvesSpdSystemWithEveryOrdering) {
  const SparseMatrix matrix = gridLaplacian(12, 0.0);
  const Eigen::VectorXd rhs = rightHandSide(matrix.rows());
  const Eigen::VectorXd reference = Eigen::MatrixXd(matrix).ldlt().solve(rhs);
  for (FillOrdering ordering : {FillOrdering::Amd, FillOrdering::Metis,
                                FillOrdering::NestedDissection, FillOrdering::Automatic}) {
    auto solver = makeCholmodSolver(ordering);
    solver->analyzePattern(matrix);
    solver->factorize(matrix);
    const Eigen::VectorXd x = solver->solve(rhs);
    EXPECT_LT((x - reference).norm(), 1e-12 * reference.norm());
    EXPECT_EQ(solver->statistics().analyses, 1);
    EXPECT_EQ(solver->statistics().factorizations, 1);
    EXPECT_EQ(solver->statistics().solves, 1);
  }
}

TEST(LinearSolver, UmfpackSolvesUnsymmetricSystem) {
  SparseMatrix matrix = gridLaplacian(10, 0.0);
  // Unsymmetric perturbation: upwind convection-like coupling on the first off-diagonal.
  for (int k = 0; k + 1 < matrix.rows(); ++k) matrix.coeffRef(k, k + 1) += 0.3 * (k % 3 == 0);
  matrix.makeCompressed();
  const Eigen::VectorXd rhs = rightHandSide(matrix.rows());
  auto solver = makeUmfpackSolver();
  solver->analyzePattern(matrix);
  solver->factorize(matrix);
  const Eigen::VectorXd x = solver->solve(rhs);
  const Eigen::VectorXd reference = Eigen::MatrixXd(matrix).partialPivLu().solve(rhs);
  EXPECT_LT((x - reference).norm(), 1e-12 * reference.norm());
}

// The sign of the determinant from UMFPACK's factor (what a failing Newton solve reports when
// its tangents have both signs, tangent_orientation.hpp): the grid Laplacian minus s I has the
// eigenvalues 4 - 2 cos(i pi / 9) - 2 cos(j pi / 9), i, j = 1..8, so its determinant has the
// sign (-1)^(number of them below s); with an unsymmetric perturbation, that of a dense LU. In
// 32- and 64-bit indices.
TEST(LinearSolver, UmfpackTellsTheSignOfTheDeterminant) {
  const double pi = std::acos(-1.0);
  for (const double narrowUnitLimit : {double(INT_MAX), 1.0}) {
    for (const double shift : {0.0, 0.5, 1.0, 2.1, 4.3}) {
      int below = 0;
      for (int i = 1; i <= 8; ++i)
        for (int j = 1; j <= 8; ++j) {
          below += 4 - 2 * std::cos(i * pi / 9) - 2 * std::cos(j * pi / 9) < shift;
        }
      SparseMatrix matrix = gridLaplacian(8, shift);
      auto solver = makeUmfpackSolver(kDefaultOrdering, narrowUnitLimit);
      EXPECT_FALSE(solver->determinantSign());  // nothing factorized yet
      solver->analyzePattern(matrix);
      solver->factorize(matrix);
      EXPECT_EQ(solver->determinantSign(), below % 2 ? -1 : 1) << shift << " " << below;
      for (int k = 0; k + 1 < matrix.rows(); ++k) matrix.coeffRef(k, k + 1) += 0.3 * (k % 3 == 0);
      matrix.makeCompressed();
      solver->analyzePattern(matrix);
      solver->factorize(matrix);
      const double dense = Eigen::MatrixXd(matrix).partialPivLu().determinant();
      EXPECT_EQ(solver->determinantSign(), dense > 0 ? 1 : -1) << shift;
    }
  }
}

// CHOLMOD factors only positive definite matrices, so a factor it made proves the sign +1; a
// matrix it rejects leaves no sign (the grid Laplacian shifted by 0.5 has a negative eigenvalue).
TEST(LinearSolver, CholmodTellsAPositiveDeterminantOnlyWithAFactor) {
  auto solver = makeCholmodSolver(kDefaultOrdering);
  const SparseMatrix positive = gridLaplacian(8, 0.0), indefinite = gridLaplacian(8, 0.5);
  EXPECT_FALSE(solver->determinantSign());
  solver->analyzePattern(positive);
  solver->factorize(positive);
  EXPECT_EQ(solver->determinantSign(), 1);
  EXPECT_THROW(solver->factorize(indefinite), StepFailure);
  EXPECT_FALSE(solver->determinantSign());
  solver->factorize(positive);
  solver->releaseFactor();
  EXPECT_FALSE(solver->determinantSign());
}

// The fold verdict of a failing step (tangent_orientation.hpp) from the last five tangents of
// its final attempt and, when that attempt is the line-search retry of a failed plain attempt
// at the same step, of the plain attempt's too: the grid Laplacian shifted by 0.5 has one
// eigenvalue below the shift (determinant sign -1, the test above), unshifted none (+1).
TEST(TangentOrientation, ALineSearchRetryIsJudgedWithThePlainAttemptBeforeIt) {
  const SparseMatrix positive = gridLaplacian(8, 0.0), negative = gridLaplacian(8, 0.5);
  const TangentOrientationWatch::Attempt plain{0.5, 0.6, 0.0, false};
  auto observeWindow = [&](TangentOrientationWatch& watch, const SparseMatrix& first) {
    watch.observe(25, negative);  // before the window: not kept
    watch.observe(26, first);
    for (int iteration = 27; iteration <= 30; ++iteration) watch.observe(iteration, positive);
  };
  TangentOrientationWatch watch;
  watch.begin(30, false, plain);
  observeWindow(watch, negative);
  EXPECT_NE(watch.describe().find("(26 -, 27 +, 28 +, 29 +, 30 +)"), std::string::npos)
      << watch.describe();
  // The retry alone has one sign; with the plain attempt's window, both.
  TangentOrientationWatch::Attempt retry = plain;
  retry.lineSearch = true;
  watch.begin(30, false, retry);
  observeWindow(watch, positive);
  EXPECT_NE(watch.describe().find("(the plain attempt, then its line-search retry: 26 -, 27 +, "
                                  "28 +, 29 +, 30 +; 26 +, 27 +, 28 +, 29 +, 30 +)"),
            std::string::npos)
      << watch.describe();
  // Not after a cut-back (another end time), nor for a stabilised attempt, nor for a plain
  // attempt after a plain one.
  for (TangentOrientationWatch::Attempt other :
       {TangentOrientationWatch::Attempt{0.5, 0.55, 0.0, true},
        TangentOrientationWatch::Attempt{0.5, 0.6, 1e-3, true}, plain}) {
    watch.begin(30, false, plain);
    observeWindow(watch, negative);
    watch.begin(30, false, other);
    observeWindow(watch, positive);
    EXPECT_EQ(watch.describe(), "") << other.endTime << " " << other.stabilization;
  }
}

// On several processes, or above kOrientationEquations, the watch keeps no copies: its verdict
// comes from the signs the run's own direct solver noted (MUMPS, UMFPACK, CHOLMOD), and where
// one of the window's signs is unknown (an iterative solve) it says nothing.
TEST(TangentOrientation, WithoutCopiesTheVerdictComesFromTheNotedSigns) {
  const SparseMatrix small = gridLaplacian(4, 0.0);
  const TangentOrientationWatch::Attempt attempt{0.5, 0.6, 0.0, false};
  const auto window = [&](TangentOrientationWatch& watch, bool noteAll) {
    for (int iteration = 26; iteration <= 30; ++iteration) {
      watch.observe(iteration, small);
      if (noteAll || iteration != 28) watch.noteSign(iteration, iteration % 2 ? -1 : 1);
    }
  };
  TangentOrientationWatch watch;
  watch.begin(30, true, attempt);  // distributed: no copies
  window(watch, true);
  EXPECT_NE(watch.describe().find("(26 +, 27 -, 28 +, 29 -, 30 +)"), std::string::npos)
      << watch.describe();
  watch.begin(30, true, attempt);
  window(watch, false);  // iteration 28's sign unknown and no copy to factorize
  EXPECT_EQ(watch.describe(), "");
  // On one process the small tangents are kept and the noted signs still win over them: all
  // five copies are positive definite, the noted signs alternate.
  watch.begin(30, false, attempt);
  window(watch, true);
  EXPECT_NE(watch.describe().find("(26 +, 27 -, 28 +, 29 -, 30 +)"), std::string::npos);
  // A sign noted for another iteration than the last observed is not taken.
  watch.begin(30, true, attempt);
  for (int iteration = 26; iteration <= 30; ++iteration) {
    watch.observe(iteration, small);
    watch.noteSign(iteration - 1, -1);
  }
  EXPECT_EQ(watch.describe(), "");
}

// UMFPACK reads the tangent's 32-bit indices in place and moves to 64-bit indices (a widened
// copy) for good once an analysis estimates a factor beyond what 32-bit indices address. The
// limit is lowered here so that the larger of two grids crosses it; both widths must solve.
TEST(LinearSolver, UmfpackMovesTo64BitIndicesForGoodWhenAFactorOutgrowsThe32BitOnes) {
  const auto unsymmetric = [](int n) {
    SparseMatrix matrix = gridLaplacian(n, 0.0);
    for (int k = 0; k + 1 < matrix.rows(); ++k) matrix.coeffRef(k, k + 1) += 0.3 * (k % 3 == 0);
    matrix.makeCompressed();
    return matrix;
  };
  const SparseMatrix small = unsymmetric(6), large = unsymmetric(30);
  auto solver = makeUmfpackSolver(kDefaultOrdering, 2e4);
  const auto expectSolves = [&](const SparseMatrix& matrix) {
    solver->analyzePattern(matrix);
    solver->factorize(matrix);
    const Eigen::VectorXd rhs = rightHandSide(matrix.rows());
    const Eigen::VectorXd reference = Eigen::MatrixXd(matrix).partialPivLu().solve(rhs);
    EXPECT_LT((solver->solve(rhs) - reference).norm(), 1e-12 * reference.norm());
    EXPECT_LT((solver->applyFactor(rhs) - reference).norm(), 1e-10 * reference.norm());
  };
  expectSolves(small);
  EXPECT_EQ(solver->name(), "UMFPACK");
  expectSolves(large);
  EXPECT_EQ(solver->name(), "UMFPACK (64-bit indices)");
  expectSolves(small);  // a small pattern again stays with the 64-bit routines
  EXPECT_EQ(solver->name(), "UMFPACK (64-bit indices)");
  EXPECT_EQ(solver->statistics().analyses, 3);  // the abandoned 32-bit analysis is not counted
  EXPECT_EQ(solver->statistics().factorizations, 3);
  EXPECT_EQ(solver->statistics().solves, 3);
}

// A large system's factorization starts from a workspace of a tenth of the analysis's factor
// estimate and grows it as needed (the compact start lowers a large run's peak memory); smaller
// systems keep UMFPACK's default start. The solution is the same to round-off (at 232 k
// equations the factor's size moved by 16 bytes: UMFPACK sizes some fronts by the memory it has).
TEST(LinearSolver, UmfpackStartsALargeSystemsWorkspaceCompactAndSolvesTheSame) {
  EXPECT_EQ(umfpackInitialAllocation(kMemoryBoundSystemFrom - 1, 1e8), 0.7);
  EXPECT_EQ(umfpackInitialAllocation(kMemoryBoundSystemFrom, 1e8), -1e7);
  EXPECT_EQ(umfpackInitialAllocation(kMemoryBoundSystemFrom, 0), 0.7);

  SparseMatrix matrix = gridLaplacian(80, 0.0);
  for (int k = 0; k + 1 < matrix.rows(); ++k) matrix.coeffRef(k, k + 1) += 0.3 * (k % 3 == 0);
  matrix.makeCompressed();
  const Eigen::VectorXd rhs = rightHandSide(matrix.rows());
  const auto solveWith = [&](Eigen::Index compactFrom, int& growths) {
    auto solver = makeUmfpackSolver(kDefaultOrdering, INT_MAX, compactFrom);
    solver->analyzePattern(matrix);
    solver->factorize(matrix);
    growths = solver->statistics().workspaceGrowths;
    return Eigen::VectorXd(solver->solve(rhs));
  };
  int compactGrowths = 0, defaultGrowths = 0;
  const Eigen::VectorXd compact = solveWith(0, compactGrowths);
  const Eigen::VectorXd usual = solveWith(matrix.rows() + 1, defaultGrowths);
  EXPECT_GT(compactGrowths, 0);
  EXPECT_EQ(defaultGrowths, 0);
  EXPECT_LT(relativeResidual(matrix, compact, rhs), 1e-13);
  EXPECT_LT((compact - usual).norm(), 1e-13 * usual.norm());
}

// A contact pattern differs from the last by a few couplings: analyzed again, it keeps the
// fill-reducing ordering of the last fresh analysis. The same grid renumbered at random is an
// unrelated pattern on which that ordering fills in far more: CHOLMOD, which counts the flops
// of an ordering in its analysis, orders it afresh at once; UMFPACK (whose analysis only bounds
// the flops) learns it from the factorization and orders its next pattern afresh.
TEST(LinearSolver, APatternCloseToTheLastKeepsItsOrderingAndAnUnrelatedOneIsOrderedAfresh) {
  const SparseMatrix base = gridLaplacian(30, 0.0);
  SparseMatrix coupled = base;  // diagonal neighbours coupled in a few cells, still SPD
  for (int k : {40, 41, 300, 512, 777}) {
    coupled.coeffRef(k, k + 31) -= 0.1;
    coupled.coeffRef(k + 31, k) -= 0.1;
    coupled.coeffRef(k, k) += 0.1;
    coupled.coeffRef(k + 31, k + 31) += 0.1;
  }
  coupled.makeCompressed();
  Eigen::VectorXi order = Eigen::VectorXi::LinSpaced(base.rows(), 0, base.rows() - 1);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> shuffle(order);
  SparseMatrix renumbered = shuffle * base * shuffle.transpose();
  renumbered.makeCompressed();
  const std::vector<const SparseMatrix*> sequence{&base, &coupled, &renumbered, &renumbered};
  // Orderings kept after each analysis of the sequence.
  const std::vector<int> cholmodReuses{0, 1, 1, 2}, umfpackReuses{0, 1, 2, 2};
  for (const bool cholmod : {true, false}) {
    SCOPED_TRACE(cholmod ? "CHOLMOD" : "UMFPACK");
    auto solver = cholmod ? makeCholmodSolver() : makeUmfpackSolver();
    for (std::size_t k = 0; k < sequence.size(); ++k) {
      const SparseMatrix& matrix = *sequence[k];
      solver->analyzePattern(matrix);
      solver->factorize(matrix);
      const Eigen::VectorXd rhs = rightHandSide(matrix.rows());
      const Eigen::VectorXd reference = Eigen::MatrixXd(matrix).ldlt().solve(rhs);
      EXPECT_LT((solver->solve(rhs) - reference).norm(), 1e-12 * reference.norm());
      EXPECT_EQ(solver->statistics().reusedOrderings, (cholmod ? cholmodReuses : umfpackReuses)[k])
          << "after analysis " << k + 1;
    }
  }
}

TEST(TangentSolver, IndefiniteSymmetricSystemFallsBackToUmfpackForTheRestOfTheStep) {
  const SparseMatrix matrix = gridLaplacian(10, 1.0);  // eigenvalues on both sides of 0
  const Eigen::VectorXd rhs = rightHandSide(matrix.rows());
  const SystemMatrices system = systemOf(matrix, true, 1);
  TangentSolver solver;
  solver.setFactorReuse(false);  // every tangent factorized: the backends are under test
  solver.factorize(system);
  EXPECT_EQ(solver.activeBackend(), "UMFPACK");
  EXPECT_EQ(solver.choleskyFallbacks(), 1);
  EXPECT_LT(relativeResidual(matrix, solver.solve(rhs), rhs), 1e-13);

  solver.factorize(system);  // same step: straight to UMFPACK
  EXPECT_EQ(solver.statistics().factorizations, 3);

  // A new step tries CHOLMOD again, which works once the matrix is positive definite (and
  // CHOLMOD refactorizes after its failed attempt with the same symbolic analysis).
  solver.beginStep();
  const SparseMatrix definite = gridLaplacian(10, 0.0);
  const SystemMatrices definiteSystem = systemOf(definite, true, 1);
  solver.factorize(definiteSystem);
  EXPECT_EQ(solver.activeBackend(), "CHOLMOD");
  EXPECT_LT(relativeResidual(definite, solver.solve(rhs), rhs), 1e-13);
  EXPECT_EQ(solver.statistics().analyses, 2);  // one per backend
}

TEST(TangentSolver, ExactlySingularSystemIsReportedByBothBackends) {
  const SystemMatrices system = systemOf(freeChain({1.0, 2.0, 1.0, 3.0}), true, 7);
  TangentSolver solver;
  try {
    solver.factorize(system);
    FAIL() << "expected StepFailure";
  } catch (const StepFailure& failure) {
    EXPECT_EQ(failure.kind(), FailureKind::SingularSystem);
    const std::string message = failure.what();
    EXPECT_NE(message.find("CHOLMOD: tangent not positive definite"), std::string::npos);
    EXPECT_NE(message.find("UMFPACK"), std::string::npos);
  }
}

TEST(TangentSolver, RoundedSingularSystemIsCaughtByThePivotRatio) {
  // Stiffnesses that are not exact binary fractions: the zero pivot comes out as round-off.
  std::vector<double> stiffness;
  for (int s = 0; s < 40; ++s)
    stiffness.push_back(0.1 + 0.37 * std::sin(3.0 * s) * std::sin(3.0 * s));
  const SystemMatrices system = systemOf(freeChain(stiffness), false, 3);
  TangentSolver solver;
  EXPECT_THROW(solver.factorize(system), StepFailure);
  const SystemMatrices symmetricSystem = systemOf(freeChain(stiffness), true, 3);
  EXPECT_THROW(solver.factorize(symmetricSystem), StepFailure);
}

TEST(TangentSolver, SymbolicAnalysisRepeatedOnlyWhenThePatternVersionChanges) {
  SparseMatrix matrix = gridLaplacian(8, 0.0);
  const Eigen::VectorXd rhs = rightHandSide(matrix.rows());
  TangentSolver solver;
  solver.setFactorReuse(false);  // every tangent factorized: the backends are under test
  for (int iteration = 1; iteration <= 10; ++iteration) {
    matrix.coeffs() *= 1.1;  // new values, same pattern
    const SystemMatrices system = systemOf(matrix, true, 42);
    solver.factorize(system);
    EXPECT_LT(relativeResidual(matrix, solver.solve(rhs), rhs), 1e-13);
  }
  EXPECT_EQ(solver.statistics().analyses, 1);
  EXPECT_EQ(solver.statistics().factorizations, 10);
  const SystemMatrices changed = systemOf(gridLaplacian(9, 0.0), true, 43);
  solver.factorize(changed);
  EXPECT_EQ(solver.statistics().analyses, 2);
  // Unsymmetric systems go to UMFPACK with its own analysis.
  const SystemMatrices unsymmetric = systemOf(gridLaplacian(9, 0.0), false, 43);
  solver.factorize(unsymmetric);
  EXPECT_EQ(solver.activeBackend(), "UMFPACK");
  EXPECT_EQ(solver.statistics().analyses, 3);
}

TEST(TangentSolver, SwitchingBackendsKeepsOneFactorAndBothAnalyses) {
  // A frictional run alternates: symmetric (CHOLMOD) while all points stick, unsymmetric
  // (UMFPACK) while they slide. The idle backend frees its numeric factor, keeps its analysis,
  // and factorizes correctly again from the symbolic factor when the run switches back.
  const SparseMatrix symmetricMatrix = gridLaplacian(10, 0.0);
  SparseMatrix unsymmetricMatrix = symmetricMatrix;
  for (int k = 0; k + 1 < unsymmetricMatrix.rows(); ++k)
    unsymmetricMatrix.coeffRef(k, k + 1) += 0.3 * (k % 3 == 0);
  const Eigen::VectorXd rhs = rightHandSide(symmetricMatrix.rows());
  // The systems outlive their solves (UMFPACK refines with the matrix it factorized).
  const SystemMatrices symmetricSystem = systemOf(symmetricMatrix, true, 7);
  const SystemMatrices unsymmetricSystem = systemOf(unsymmetricMatrix, false, 7);
  TangentSolver solver;
  solver.setFactorReuse(false);  // every tangent factorized: the backends are under test
  for (int round = 0; round < 3; ++round) {
    solver.factorize(symmetricSystem);
    EXPECT_EQ(solver.activeBackend(), "CHOLMOD");
    EXPECT_LT(relativeResidual(symmetricMatrix, solver.solve(rhs), rhs), 1e-13);
    solver.factorize(unsymmetricSystem);
    EXPECT_EQ(solver.activeBackend(), "UMFPACK");
    EXPECT_LT(relativeResidual(unsymmetricMatrix, solver.solve(rhs), rhs), 1e-13);
  }
  EXPECT_EQ(solver.statistics().analyses, 2);  // one per backend, never repeated
  EXPECT_EQ(solver.statistics().factorizations, 6);
}

// The tangents of one Newton step: the same grid operator with its entries scaled by
// 1 + amplitude * sin(entry), a pattern version of their own each (contact moves entries).
SparseMatrix perturbed(const SparseMatrix& base, double amplitude, int seed) {
  SparseMatrix matrix = base;
  for (Eigen::Index k = 0; k < matrix.nonZeros(); ++k) {
    matrix.valuePtr()[k] *= 1 + amplitude * std::sin(1.7 * static_cast<double>(k + seed));
  }
  return matrix;
}

TEST(TangentSolver, LaterTangentsAreSolvedWithTheFirstFactorToTheReuseTolerance) {
  const SparseMatrix base = gridLaplacian(30, 0.0);
  const Eigen::VectorXd rhs = rightHandSide(base.rows());
  TangentSolver solver;
  for (int iteration = 0; iteration < 6; ++iteration) {
    // Unsymmetric from the second tangent on, as when friction starts to slip.
    const SparseMatrix matrix = perturbed(base, iteration == 0 ? 0.0 : 1e-3, iteration);
    const SystemMatrices system = systemOf(matrix, iteration == 0, 10 + iteration);
    solver.factorize(system);
    const Eigen::VectorXd solution = solver.solve(rhs);
    const Eigen::VectorXd exact = Eigen::MatrixXd(matrix).lu().solve(rhs);
    EXPECT_LT(relativeResidual(matrix, solution, rhs), kReusedFactorResidual) << iteration;
    EXPECT_LT((solution - exact).norm(), 1e-10 * exact.norm()) << iteration;
  }
  const LinearSolverStatistics work = solver.statistics();
  EXPECT_EQ(work.factorizations, 1);
  EXPECT_EQ(work.analyses, 1);
  EXPECT_EQ(work.reusedPreconditioners, 5);
  EXPECT_EQ(work.solves, 6);
  // A 1e-3 change leaves a few GMRES iterations per solve, well inside the allowance.
  EXPECT_GE(work.krylovIterations, 5);
  EXPECT_LE(work.krylovIterations, 5 * 10);
  EXPECT_EQ(solver.activeBackend(), "CHOLMOD");  // the factor that served them all
}

TEST(TangentSolver, ATangentTooFarFromTheFactorIsFactorizedAfterAll) {
  const SparseMatrix base = gridLaplacian(30, 0.0);
  const Eigen::VectorXd rhs = rightHandSide(base.rows());
  TangentSolver solver;
  const SystemMatrices first = systemOf(base, true, 1);
  solver.factorize(first);
  (void)solver.solve(rhs);
  // Entries changed by up to 90 %: the old factor is no preconditioner for this one.
  const SparseMatrix far = perturbed(base, 0.9, 3);
  const SystemMatrices second = systemOf(far, false, 2);
  solver.factorize(second);
  const Eigen::VectorXd solution = solver.solve(rhs);
  EXPECT_LT(relativeResidual(far, solution, rhs), 1e-13);  // a direct solve's accuracy
  EXPECT_EQ(solver.activeBackend(), "UMFPACK");
  const LinearSolverStatistics work = solver.statistics();
  EXPECT_EQ(work.factorizations, 2);
  EXPECT_EQ(work.reusedPreconditioners, 0);
  EXPECT_EQ(work.krylovIterations, kReusedFactorIterations);  // the attempt that was given up
}

TEST(TangentSolver, WithoutReuseEveryTangentIsFactorized) {
  const SparseMatrix base = gridLaplacian(12, 0.0);
  const Eigen::VectorXd rhs = rightHandSide(base.rows());
  TangentSolver solver;
  solver.setFactorReuse(false);
  for (int iteration = 0; iteration < 4; ++iteration) {
    const SparseMatrix matrix = perturbed(base, 1e-3, iteration);
    const SystemMatrices system = systemOf(matrix, false, 5);
    solver.factorize(system);
    EXPECT_LT(relativeResidual(matrix, solver.solve(rhs), rhs), 1e-13);
  }
  EXPECT_EQ(solver.statistics().factorizations, 4);
  EXPECT_EQ(solver.statistics().reusedPreconditioners, 0);
  EXPECT_EQ(solver.statistics().krylovIterations, 0);
}

}  // namespace
}  // namespace cc
