// Assembler: evaluates Contributions item by item in parallel (OpenMP, colored so that no two
// items of one color share a node: no locks on the hot path) and scatters into the global
// nodal force vector and the sparse tangent blocks K_ff (free x free) and K_fp (free x
// prescribed). The sparsity pattern is rebuilt only when a contribution's topology changes.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "fem/contribution.hpp"
#include "fem/dof_map.hpp"
#include "fem/sparse_matrix.hpp"

namespace cc {

// A pattern version no assembler has handed out (a process whose own pattern did not change
// while another's did takes one, so that all of them analyze again together).
std::uint64_t newPatternVersion();

struct SystemMatrices {
  SparseMatrix free;                 // K_ff: numFree x numFree (full storage, both triangles)
  SparseMatrix coupling;             // K_fp: numFree x numPrescribed
  bool symmetric = true;             // every contribution reported a symmetric tangent
  std::uint64_t patternVersion = 0;  // changes with the pattern; unique in the process, 0 = none
};

// Wall time of one contribution's parts, accumulated over calls.
struct ContributionTimings {
  double prepare = 0;   // Contribution::prepare
  double evaluate = 0;  // its items' evaluation + scatter
};

// Wall time spent in the parts of an assembly and how often the expensive set-up ran,
// accumulated over calls (for benchmarks and tests).
struct AssemblyTimings {
  double prepare = 0;       // Contribution::prepare (contact search, projection)
  double evaluate = 0;      // item evaluation + scatter
  double pattern = 0;       // pattern and coloring rebuilds
  int assemblies = 0;       // calls of assemble()
  int colorings = 0;        // item colorings computed (one per contribution topology change)
  int patternBuilds = 0;    // sparsity pattern constructions
  int patternVersions = 0;  // constructions that changed the pattern (each needs an analysis)
  // The same split per contribution, in the order the Assembler was given them (so that a
  // benchmark can tell element from contact cost).
  std::vector<ContributionTimings> byContribution;
};

class Assembler {
 public:
  // Keeps references: `dofs` and the contributions must outlive the assembler.
  Assembler(const DofMap& dofs, std::vector<Contribution*> contributions);
  ~Assembler();

  // Adds all contributions at `state` into `force` (3 * numNodes, zeroed here) and, if
  // `tangent` is given, into its matrices (pattern kept or rebuilt, values zeroed here).
  // Pass the same SystemMatrices every time: the pattern lives only there (no second copy),
  // and it is rebuilt when a topology changed or `tangent` holds another pattern version. A
  // rebuild that reproduces the old pattern keeps its version (no new symbolic analysis).
  // Throws StepFailure naming the first failing item (NaN, inverted element, projection...).
  void assemble(const AssemblyState& state, Eigen::VectorXd& force, SystemMatrices* tangent);

  const AssemblyTimings& timings() const { return timings_; }
  int threads() const;
  // Restricts the items evaluated and added (contribution index in the constructor's order).
  // `ownedNodes` (one flag per node, on several processes) makes the pattern's rows of the
  // owned nodes complete (buildNodeGraph).
  void setItemFilter(ItemFilter filter, std::vector<char> ownedNodes = {});
  // Contributions with less work per color than this many Hex8 elements spread over 8 colors
  // are evaluated on one thread (default 256; each contribution's items weighted by their
  // measured cost, see assembler.cpp).
  void setMinItemsForThreads(std::size_t items);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  AssemblyTimings timings_;
};

}  // namespace cc
