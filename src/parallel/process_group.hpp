// ProcessGroup: the processes of one run (`mpirun -np N covcontact run DECK`) and the few
// collective operations the model and the command need of them: sums of nodal vectors, one
// decision or one error for all, and a partition of the mesh. A serial run (no mpirun, or
// -np 1) has the one-process group, which needs neither MPI nor PETSc; with more processes the
// group comes from the PETSc plugin (mpi_group.cpp), the only code that calls MPI. Element,
// material and contact kernels never see it; the model decides what each process evaluates.
//
// Every operation is collective: all processes call it at the same point of the same control
// flow. The flow stays the same everywhere because everything a decision is taken on is
// replicated bit for bit (sums are reduced on rank 0 and broadcast, not all-reduced, whose
// summation order may differ between ranks).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "parallel/launch_environment.hpp"

namespace cc {

class ProcessGroup {
 public:
  virtual ~ProcessGroup() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Element-wise sum over the processes; every process receives the same bits.
  virtual void sum(double* values, std::size_t count) = 0;
  virtual int maximum(int value) = 0;
  // The code and message of the lowest rank whose code is not 0, on every rank ({0, ""} when
  // every code is 0): one error, reported once, ends every process the same way.
  virtual std::pair<int, std::string> agree(int code, const std::string& message) = 0;
  // Owner rank of every vertex of a graph (CSR: neighbours of vertex v are
  // adjacency[offsets[v] .. offsets[v + 1]), no self-loops), parts balanced in vertex count
  // and few cut edges (Scotch on rank 0); the same vector on every process and in every run.
  virtual std::vector<int> partition(const std::vector<int>& offsets,
                                     const std::vector<int>& adjacency) = 0;
  // Sets up two HDF5 property lists (ids as hid_t) so that the processes open one file
  // together through MPI-IO and transfer its data collectively (the results writer's
  // ParallelOutput). Only for more than one process: a serial run writes without MPI.
  virtual void useCollectiveFile(std::int64_t fileAccess, std::int64_t transfer) = 0;
  // Ends every process of the run at once with `code`: for a process that cannot go on while
  // the others would wait for it in the next collective operation.
  [[noreturn]] virtual void abort(int code) = 0;
  // Bytes the group's own operations (sum, agree, ...) moved between processes so far, all
  // processes together, counting what each message carries (not the transport's overhead).
  virtual double bytesMoved() const { return 0; }
};

// The process's group: the MPI one when launchedProcesses() > 1 (loads the PETSc plugin and
// initializes MPI on first call), else the one-process group.
ProcessGroup& processGroup();

}  // namespace cc
