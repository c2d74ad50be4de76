// Sparsity pattern of the global tangent: the node graph of all items of all contributions,
// expanded to the free x free (K_ff) and free x prescribed (K_fp) blocks in compressed columns.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "fem/contribution.hpp"
#include "fem/dof_map.hpp"
#include "fem/sparse_matrix.hpp"

namespace cc {

// Neighbours of every node (itself included, ascending): nodes sharing an item with it.
struct NodeGraph {
  std::vector<std::int64_t> offsets;  // neighbours of n: neighbours[offsets[n]..offsets[n+1])
  std::vector<int> neighbours;
};

// With a filter, only the items this process assembles (ItemRole::Assemble) count; every node
// keeps itself as neighbour (the diagonal blocks). With a filter and `ownedNodes` (one flag per
// node: its rows are this process's), the rows of the owned nodes are complete: the other
// processes' items with an owned node add their node pairs to these rows, as entries this
// process leaves zero. PETSc's matrix then takes each process's own rows as they are, and only
// the values another process adds travel (parallel/petsc_solver.cpp).
NodeGraph buildNodeGraph(std::span<Contribution* const> contributions, int numNodes,
                         const ItemFilter& filter = {}, std::span<const char> ownedNodes = {});

// Resizes `free` and `coupling` to the pattern of `graph` with zero values. Because equations
// are numbered node by node, visiting neighbours in ascending order yields sorted row indices.
void buildSparsityPattern(const DofMap& dofs, const NodeGraph& graph, SparseMatrix& free,
                          SparseMatrix& coupling);

// Same structure (dimensions, column pointers, row indices); values are ignored.
bool samePattern(const SparseMatrix& a, const SparseMatrix& b);

}  // namespace cc
