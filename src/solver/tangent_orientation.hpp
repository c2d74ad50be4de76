// Tangent orientation of a failing Newton solve: the signs of the determinants of the last
// iterations' tangents, for the failure message. Where contact points keep switching and the
// tangents of the states Newton passes through have determinants of both signs, the residual
// folds over there: it has no locally unique zero near the iterates, and no smaller step or
// line search gets through. That is a limit point of the discrete frictional problem (a
// stick/slip instability, Klarbring's non-uniqueness), not a solver fault, and the message says
// so (issue 14: ironing_nts_mu06_equal stops at t = 0.667 with a slab edge node under the die's
// free edge switching stick/slip; one of its tangents has the eigenvalue -0.35, the other none
// below +0.0067; docs/verification/sliding.md, twenty-sixth session).
#pragma once

#include <Eigen/Core>
#include <deque>
#include <optional>
#include <string>

#include "fem/sparse_matrix.hpp"

namespace cc {

// Iterations whose tangents are watched: the stick/slip cycles measured repeat within 2-5.
inline constexpr int kOrientationWindow = 5;
// Free equations up to which a copy of a tangent is kept, for the iterations whose solve does
// not tell its determinant's sign (an iterative solve, a reused factor): five factorizations of
// a 3D tangent of 20 000 equations take about 20 s on one thread (4.3 s each,
// docs/performance/solvers.md), a bounded price for the message of a run that has given up.
// Larger systems, and runs on several processes, get a verdict only from signs their direct
// solver reported (noteSign).
inline constexpr Eigen::Index kOrientationEquations = 20000;

class TangentOrientationWatch {
 public:
  // What tells a line-search retry of a failed plain attempt: the same step (start and end
  // time) and stabilisation factor, without and then with the line search.
  struct Attempt {
    double startTime = -1;
    double endTime = -1;
    double stabilization = 0;
    bool lineSearch = false;
  };
  // Watches the tangents of the last kOrientationWindow iterations of an attempt of at most
  // maxIterations (copies only up to kOrientationEquations equations, on one process). The
  // line-search retry of a failed plain attempt keeps those of the plain attempt as well: both
  // start from the same converged state, and which of the two passes through tangents of both signs
  // depends on round-off in the path (ironing_nts_mu06_equal: the retry's up to the
  // forty-fourth session; since an active-set cycle near convergence no longer ends the plain
  // attempt, the plain attempt's).
  void begin(int maxIterations, bool distributed, const Attempt& attempt) {
    const bool retry = attempt.startTime == attempt_.startTime &&
                       attempt.endTime == attempt_.endTime &&
                       attempt.stabilization == attempt_.stabilization && !attempt_.lineSearch &&
                       attempt.lineSearch;
    earlier_.clear();
    if (retry) earlier_.swap(kept_);
    kept_.clear();
    from_ = maxIterations - kOrientationWindow + 1;
    distributed_ = distributed;
    attempt_ = attempt;
  }
  // The tangent assembled at `iteration` (watched only within the window: no cost before it).
  void observe(int iteration, const SparseMatrix& tangent);
  // The sign of that tangent's determinant as the run's own factorization found it (0:
  // singular), where its solver could tell (TangentSolver::determinantSign).
  void noteSign(int iteration, std::optional<int> sign);
  // The signs of the watched tangents of both attempts: noted, else from a factorization of the
  // kept copy (UMFPACK). If every one is known and they have both signs, returns the sentence
  // for the failure message; else an empty string.
  std::string describe() const;

 private:
  struct Kept {
    int iteration;
    std::optional<SparseMatrix> tangent;  // a copy, where the system is small enough
    std::optional<int> sign;              // noted from the run's own factorization
  };
  std::deque<Kept> kept_;
  std::deque<Kept> earlier_;  // the window of the plain attempt a line-search retry follows
  Attempt attempt_;
  int from_ = 0;
  bool distributed_ = false;
};

}  // namespace cc
