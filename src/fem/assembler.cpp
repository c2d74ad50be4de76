// Parallel assembly: per contribution, items of one color run in an OpenMP loop, each thread
// with its own local buffers, and scatter straight into the force vector and the compressed
// columns of K_ff / K_fp (colors guarantee disjoint writes, so no locks or atomics).
#include "fem/assembler.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <chrono>
#include <cmath>
#include <exception>
#include <optional>
#include <string>

#include "common/stopwatch.hpp"
#include "fem/coloring.hpp"
#include "fem/sparsity_pattern.hpp"

namespace cc {

namespace {

// Items handed to a thread at a time: large enough to amortize scheduling, small enough to
// balance elements of very different cost (contact items next to empty ones).
constexpr int kScheduleChunk = 16;

// Contributions with too little work per color run on one thread. Threads pay one barrier per
// color, where the thread that finishes first sleeps (OMP_WAIT_POLICY=passive) and is woken
// again: ~50 us per barrier on this workplace's 2-core machines (57 k scaling deck: 4.19 s of
// elements with spinning threads, 4.46 s sleeping). On a machine whose cores are busy with other
// work a barrier can wait a whole time slice for a descheduled thread (measured in an earlier
// session: the 500-element main example took 15 s on one thread and 70-90 s on two on a loaded
// 2-core machine). The rule is one of work per color: a contribution goes parallel when its
// work divided by its colors reaches that of minItemsForThreads items of kReferenceItemCpuSeconds
// spread over kReferenceColors colors (the 8 of a structured Hex8 mesh), 0.19 ms by default.
// Measured (docs/performance/solvers.md, twenty-fifth session): the scaling decks' base blocks
// and contact kernels (0.2-1.1 ms per color), which a threshold of 2 048 items per contribution
// kept on one thread, go parallel (elements + contact kernel on two threads 1.42-1.67x faster
// at 20 k instead of 1.24-1.35x, 1.39-1.79x at 57 k instead of 1.45-1.47x); example 6.1's
// block (400 elements, ~0.3 ms per color) assembles 25 % faster on two threads for 10 % more
// CPU; its contact kernel and base stay on one. A process busy on one of the two cores left a
// 20 k run on two threads as fast as on one either way; threads spinning at the barriers
// (GOMP_SPINCOUNT) made it 1.5 times slower.
constexpr std::size_t kDefaultMinItemsForThreads = 256;
constexpr double kReferenceColors = 8;
// The threshold is one of work, not of items: minItemsForThreads items of this CPU cost (a Hex8
// element with its tangent, 5.7-7.4 us measured on the paper's and the ironing decks). Each
// contribution's own cost per item is measured (thread CPU time, which load does not inflate)
// and weighs its item count, so that 1 728 contact points with an AD tangent (12-26 us each)
// go parallel where 1 728 cheap items would not (issue 13, item 7). The first evaluation, not
// yet measured, counts items. Serial and parallel evaluation add in the same order (by color),
// so the choice never changes a result.
constexpr double kReferenceItemCpuSeconds = 6e-6;

// Pattern versions are unique in the process so that a solver keyed on a version never
// confuses patterns of two assemblers.
std::atomic<std::uint64_t> nextPatternVersion{1};

}  // namespace

// Types that Assembler::Impl's members hold: in a named namespace, since an anonymous one gives
// Impl members of internal linkage (-Wsubobject-linkage in the unity build).
namespace assembly_buffers {

// Identity of an item list: the pattern and coloring follow it.
struct TopologyKey {
  std::uint64_t version = 0;
  std::size_t itemCount = 0;
  bool operator==(const TopologyKey&) const = default;
};

TopologyKey topologyOf(const Contribution& contribution) {
  return {contribution.topologyVersion(), contribution.itemCount()};
}

// Per item size: local vectors reused across items (no allocation on the hot path).
struct LocalBuffers {
  Eigen::VectorXd force;
  Eigen::MatrixXd tangent;
  std::vector<int> equations;      // free equation of each local dof, or -1
  std::vector<int> prescribed;     // prescribed index of each local dof, or -1
  std::vector<int> firstEquation;  // smallest free equation of each local node, or -1
  std::vector<int> rowOffsets;     // each local node's first row within a block column
};

// Whether every entry is finite: x * 0 is NaN exactly for an infinite or NaN x, and the sum of
// the products is NaN exactly if one of them is. Eigen's allFinite() compares entry by entry in
// a scalar loop, which took a quarter of the scatter's time on example 6.1 (24 x 24 element
// matrices); the sum is vectorized.
template <class Derived>
bool allFinite(const Eigen::DenseBase<Derived>& values) {
  const double probe = (values.derived().array() * 0.0).sum();
  return probe == probe;
}

// The first failure one thread met (items are visited in ascending order within a color).
struct ItemFailure {
  bool failed = false;
  std::size_t item = 0;
  FailureKind kind = FailureKind::NotFinite;
  std::string detail;
  std::exception_ptr error;  // a non-StepFailure exception (a bug), rethrown after the loop

  void record(std::size_t failedItem, FailureKind failureKind, std::string text,
              std::exception_ptr exception = nullptr) {
    if (failed && item <= failedItem) return;
    failed = true;
    item = failedItem;
    kind = failureKind;
    detail = std::move(text);
    error = exception;
  }
};

struct ThreadBuffers {
  std::vector<LocalBuffers> bySize;  // indexed by the item's node count
  ItemFailure failure;

  LocalBuffers& forNodes(std::size_t numNodes, bool withTangent) {
    if (bySize.size() <= numNodes) bySize.resize(numNodes + 1);
    LocalBuffers& local = bySize[numNodes];
    const Eigen::Index size = static_cast<Eigen::Index>(3 * numNodes);
    if (local.force.size() != size) {
      local.force.resize(size);
      local.equations.resize(3 * numNodes);
      local.prescribed.resize(3 * numNodes);
      local.firstEquation.resize(numNodes);
      local.rowOffsets.resize(numNodes);
    }
    if (withTangent && local.tangent.rows() != size) local.tangent.resize(size, size);
    return local;
  }
};

}  // namespace assembly_buffers

namespace {

using assembly_buffers::allFinite;
using assembly_buffers::ItemFailure;
using assembly_buffers::LocalBuffers;
using assembly_buffers::ThreadBuffers;
using assembly_buffers::TopologyKey;
using assembly_buffers::topologyOf;

// Where each local node's rows start in the block columns of one column node. Every column of a
// node, free (in `free`) or prescribed (in `coupling`), has the same rows: the free equations
// of the node's neighbours, ascending (sparsity_pattern.cpp). So one binary search per
// (column node, row node) pair serves all three columns of the node; rows of one node's free
// dofs are consecutive equations and therefore consecutive entries.
void locateRows(LocalBuffers& local, const SparseMatrix& block, int blockColumn) {
  const int* rowsBegin = block.innerIndexPtr() + block.outerIndexPtr()[blockColumn];
  const int* rowsEnd = block.innerIndexPtr() + block.outerIndexPtr()[blockColumn + 1];
  for (std::size_t k = 0; k < local.firstEquation.size(); ++k) {
    const int first = local.firstEquation[k];
    if (first < 0) continue;
    const int* found = std::lower_bound(rowsBegin, rowsEnd, first);
    assert(found != rowsEnd && *found == first && "pattern lacks a node pair of an item");
    local.rowOffsets[k] = static_cast<int>(found - rowsBegin);
  }
}

// Adds local column `localColumn` to a compressed block column whose rows locateRows() found.
void scatterColumn(const LocalBuffers& local, int localColumn, int blockColumn,
                   SparseMatrix& block) {
  const std::ptrdiff_t columnStart = block.outerIndexPtr()[blockColumn];
  double* values = block.valuePtr();
  const std::size_t numNodes = local.firstEquation.size();
  for (std::size_t k = 0; k < numNodes; ++k) {
    const int first = local.firstEquation[k];
    if (first < 0) continue;
    const std::ptrdiff_t base = columnStart + local.rowOffsets[k];
    assert(block.innerIndexPtr()[base] == first && "columns of one node differ in rows");
    for (int component = 0; component < 3; ++component) {
      const int row = local.equations[3 * k + component];
      if (row >= 0) {
        values[base + (row - first)] +=
            local.tangent(static_cast<Eigen::Index>(3 * k + component), localColumn);
      }
    }
  }
}

}  // namespace

struct Assembler::Impl {
  struct ContributionState {
    std::optional<TopologyKey> colored;
    ItemColoring coloring;
    // Measured CPU seconds per item of the last evaluation, [0] without and [1] with the
    // tangent; negative until measured.
    std::array<double, 2> cpuSecondsPerItem{-1, -1};
  };

  const DofMap& dofs;
  std::vector<Contribution*> contributions;
  std::vector<ContributionState> states;
  std::vector<TopologyKey> patternKeys;  // topologies the current pattern was built from
  std::uint64_t patternVersion = 0;
  std::vector<ThreadBuffers> threadBuffers;
  std::size_t minItemsForThreads = kDefaultMinItemsForThreads;
  ItemFilter filter;
  std::vector<char> ownedNodes;  // empty on one process

  Impl(const DofMap& dofMap, std::vector<Contribution*> list)
      : dofs(dofMap), contributions(std::move(list)), states(contributions.size()) {}

  bool recolorChanged(AssemblyTimings& timings);
  bool patternStale(const SystemMatrices& tangent) const;
  void rebuildPattern(SystemMatrices& tangent, AssemblyTimings& timings);
  void evaluateItem(Contribution& contribution, std::size_t item, const AssemblyState& state,
                    ThreadBuffers& buffers, Eigen::VectorXd& force, SystemMatrices* tangent,
                    bool scatter);
  void evaluateContribution(std::size_t index, const AssemblyState& state, Eigen::VectorXd& force,
                            SystemMatrices* tangent);
};

bool Assembler::Impl::recolorChanged(AssemblyTimings& timings) {
  bool changed = false;
  for (std::size_t c = 0; c < contributions.size(); ++c) {
    const TopologyKey key = topologyOf(*contributions[c]);
    if (states[c].colored == key) continue;
    states[c].coloring = colorItems(*contributions[c], dofs.numNodes());
    states[c].colored = key;
    ++timings.colorings;
    changed = true;
  }
  return changed;
}

bool Assembler::Impl::patternStale(const SystemMatrices& tangent) const {
  if (patternVersion == 0 || tangent.patternVersion != patternVersion) return true;
  for (std::size_t c = 0; c < contributions.size(); ++c) {
    if (!(patternKeys[c] == topologyOf(*contributions[c]))) return true;
  }
  return false;
}

void Assembler::Impl::rebuildPattern(SystemMatrices& tangent, AssemblyTimings& timings) {
  const NodeGraph graph = buildNodeGraph(contributions, dofs.numNodes(), filter, ownedNodes);
  SparseMatrix free, coupling;
  buildSparsityPattern(dofs, graph, free, coupling);
  ++timings.patternBuilds;
  patternKeys.clear();
  for (const Contribution* contribution : contributions) {
    patternKeys.push_back(topologyOf(*contribution));
  }
  const bool unchanged = tangent.patternVersion != 0 && samePattern(free, tangent.free) &&
                         samePattern(coupling, tangent.coupling);
  tangent.free = std::move(free);
  tangent.coupling = std::move(coupling);
  if (!unchanged) {
    tangent.patternVersion = nextPatternVersion++;
    ++timings.patternVersions;
  }
  patternVersion = tangent.patternVersion;
}

void Assembler::Impl::evaluateItem(Contribution& contribution, std::size_t item,
                                   const AssemblyState& state, ThreadBuffers& buffers,
                                   Eigen::VectorXd& force, SystemMatrices* tangent, bool scatter) {
  const std::span<const int> nodes = contribution.itemNodes(item);
  LocalBuffers& local = buffers.forNodes(nodes.size(), tangent != nullptr);
  local.force.setZero();
  if (tangent) local.tangent.setZero();
  LocalStatus status;
  try {
    status = contribution.evaluate(item, state, local.force, tangent ? &local.tangent : nullptr);
  } catch (const StepFailure& failure) {
    status = LocalStatus::failure(failure.kind(), failure.what());
  } catch (...) {
    buffers.failure.record(item, FailureKind::NotFinite, "exception", std::current_exception());
    return;
  }
  if (!status.ok) {
    buffers.failure.record(item, status.kind, std::move(status.detail));
    return;
  }
  if (!allFinite(local.force) || (tangent && !allFinite(local.tangent))) {
    buffers.failure.record(item, FailureKind::NotFinite, "non-finite local force or tangent");
    return;
  }
  if (!scatter) return;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    force.segment<3>(3 * static_cast<Eigen::Index>(nodes[k])) += local.force.segment<3>(3 * k);
  }
  if (!tangent) return;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    local.firstEquation[k] = -1;
    for (int component = 0; component < 3; ++component) {
      const int dof = 3 * nodes[k] + component;
      local.equations[3 * k + component] = dofs.equation(dof);
      local.prescribed[3 * k + component] = dofs.prescribedIndex(dof);
      if (local.firstEquation[k] < 0) local.firstEquation[k] = dofs.equation(dof);
    }
  }
  for (std::size_t m = 0; m < nodes.size(); ++m) {
    bool rowsLocated = false;
    for (int component = 0; component < 3; ++component) {
      const int column = static_cast<int>(3 * m) + component;
      const bool free = local.equations[column] >= 0;
      if (!free && local.prescribed[column] < 0) continue;
      SparseMatrix& block = free ? tangent->free : tangent->coupling;
      const int blockColumn = free ? local.equations[column] : local.prescribed[column];
      if (!rowsLocated) locateRows(local, block, blockColumn);
      rowsLocated = true;
      scatterColumn(local, column, blockColumn, block);
    }
  }
}

void Assembler::Impl::evaluateContribution(std::size_t index, const AssemblyState& state,
                                           Eigen::VectorXd& force, SystemMatrices* tangent) {
  Contribution& contribution = *contributions[index];
  const ItemColoring& coloring = states[index].coloring;
  for (ThreadBuffers& buffers : threadBuffers) buffers.failure = ItemFailure{};
  double& perItem = states[index].cpuSecondsPerItem[tangent ? 1 : 0];
  const double items = static_cast<double>(coloring.items.size());
  const double work = items * (perItem >= 0 ? perItem : kReferenceItemCpuSeconds);
  const double colors = static_cast<double>(std::max<std::size_t>(coloring.numColors(), 1));
  const bool threads = work / colors >= static_cast<double>(minItemsForThreads) *
                                            kReferenceItemCpuSeconds / kReferenceColors;
  double cpuSeconds = 0;
#pragma omp parallel if (threads) reduction(+ : cpuSeconds)
  {
    const double threadStart = threadCpuSeconds();
    ThreadBuffers& buffers = threadBuffers[omp_get_thread_num()];
    for (std::size_t color = 0; color < coloring.numColors(); ++color) {
      const std::ptrdiff_t begin = static_cast<std::ptrdiff_t>(coloring.colorBegin[color]);
      const std::ptrdiff_t end = static_cast<std::ptrdiff_t>(coloring.colorBegin[color + 1]);
#pragma omp for schedule(dynamic, kScheduleChunk)
      for (std::ptrdiff_t k = begin; k < end; ++k) {
        const std::size_t item = coloring.items[k];
        const ItemRole role = filter ? filter(index, item) : ItemRole::Assemble;
        if (role == ItemRole::Skip) continue;
        evaluateItem(contribution, item, state, buffers, force, tangent,
                     role == ItemRole::Assemble);
      }
    }
    cpuSeconds += threadCpuSeconds() - threadStart;
  }
  if (items > 0) perItem = cpuSeconds / items;
  ItemFailure first;
  for (const ThreadBuffers& buffers : threadBuffers) {
    const ItemFailure& failure = buffers.failure;
    if (failure.failed) first.record(failure.item, failure.kind, failure.detail, failure.error);
  }
  if (!first.failed) return;
  if (first.error) std::rethrow_exception(first.error);
  throw StepFailure(first.kind, contribution.name() + " item " + std::to_string(first.item) + ": " +
                                    first.detail);
}

std::uint64_t newPatternVersion() {
  return nextPatternVersion++;
}

Assembler::Assembler(const DofMap& dofs, std::vector<Contribution*> contributions)
    : impl_(std::make_unique<Impl>(dofs, std::move(contributions))) {}

Assembler::~Assembler() = default;

void Assembler::setMinItemsForThreads(std::size_t items) {
  impl_->minItemsForThreads = items;
}

void Assembler::setItemFilter(ItemFilter filter, std::vector<char> ownedNodes) {
  impl_->filter = std::move(filter);
  impl_->ownedNodes = std::move(ownedNodes);
}

int Assembler::threads() const {
  return omp_get_max_threads();
}

namespace {

void throwIfNotFinite(const Eigen::VectorXd& force) {
  for (Eigen::Index dof = 0; dof < force.size(); ++dof) {
    if (!std::isfinite(force[dof])) {
      throw StepFailure(FailureKind::NotFinite,
                        "assembled force vector: non-finite value at node " +
                            std::to_string(dof / 3) + " component " + "xyz"[dof % 3]);
    }
  }
}

}  // namespace

void Assembler::assemble(const AssemblyState& state, Eigen::VectorXd& force,
                         SystemMatrices* tangent) {
  ++timings_.assemblies;
  const std::size_t count = impl_->contributions.size();
  timings_.byContribution.resize(count);
  auto start = std::chrono::steady_clock::now();
  for (std::size_t c = 0; c < count; ++c) {
    const auto contributionStart = std::chrono::steady_clock::now();
    Contribution& contribution = *impl_->contributions[c];
    const LocalStatus status = contribution.prepare(state);
    timings_.byContribution[c].prepare += secondsSince(contributionStart);
    if (!status.ok) throw StepFailure(status.kind, contribution.name() + ": " + status.detail);
  }
  timings_.prepare += secondsSince(start);

  start = std::chrono::steady_clock::now();
  impl_->recolorChanged(timings_);
  if (tangent && impl_->patternStale(*tangent)) impl_->rebuildPattern(*tangent, timings_);
  timings_.pattern += secondsSince(start);

  start = std::chrono::steady_clock::now();
  impl_->threadBuffers.resize(static_cast<std::size_t>(omp_get_max_threads()));
  force.setZero(3 * static_cast<Eigen::Index>(impl_->dofs.numNodes()));
  if (tangent) {
    tangent->free.coeffs().setZero();
    tangent->coupling.coeffs().setZero();
  }
  bool symmetric = true;
  for (std::size_t c = 0; c < count; ++c) {
    const auto contributionStart = std::chrono::steady_clock::now();
    impl_->evaluateContribution(c, state, force, tangent);
    timings_.byContribution[c].evaluate += secondsSince(contributionStart);
    symmetric = symmetric && impl_->contributions[c]->tangentSymmetric();
  }
  if (tangent) tangent->symmetric = symmetric;
  timings_.evaluate += secondsSince(start);
  throwIfNotFinite(force);
}

}  // namespace cc
