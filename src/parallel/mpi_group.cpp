// The ProcessGroup of a run on several processes: MPI_COMM_WORLD (PETSC_COMM_WORLD), with the
// mesh partitioned by PT-Scotch through PETSc's MatPartitioning. Part of the PETSc plugin: the
// only code of the program that calls MPI.
#include <fmt/format.h>
#include <hdf5.h>
#include <mpi.h>
#include <petscmat.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "parallel/petsc_runtime.hpp"
#include "parallel/process_group.hpp"

namespace cc {

namespace {

void check(int code, const char* what) {
  if (code != 0)
    throw std::runtime_error(fmt::format("MPI/PETSc: {} failed (error {})", what, code));
}

class MpiGroup final : public ProcessGroup {
 public:
  MpiGroup() {
    petsc::ensureInitialized();
    communicator_ = PETSC_COMM_WORLD;
    MPI_Comm_rank(communicator_, &rank_);
    MPI_Comm_size(communicator_, &size_);
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void sum(double* values, std::size_t count) override {
    // Reduce to rank 0, then broadcast: every rank gets rank 0's bits (an all-reduce may add
    // in a different order on different ranks, and the ranks' decisions must agree).
    constexpr std::size_t kChunk = std::size_t(1) << 26;  // counts are ints in MPI
    for (std::size_t first = 0; first < count; first += kChunk) {
      const int n = static_cast<int>(std::min(kChunk, count - first));
      double* part = values + first;
      check(MPI_Reduce(rank_ == 0 ? MPI_IN_PLACE : part, rank_ == 0 ? part : nullptr, n, MPI_DOUBLE,
                       MPI_SUM, 0, communicator_),
            "MPI_Reduce");
      check(MPI_Bcast(part, n, MPI_DOUBLE, 0, communicator_), "MPI_Bcast");
    }
    // Whatever the algorithm, each of the other processes sends its share and receives the sum.
    moved_ += 2.0 * (size_ - 1) * static_cast<double>(count) * sizeof(double);
  }
  double bytesMoved() const override { return moved_; }

  int maximum(int value) override {
    int result = 0;
    check(MPI_Allreduce(&value, &result, 1, MPI_INT, MPI_MAX, communicator_), "MPI_Allreduce");
    return result;
  }

  std::pair<int, std::string> agree(int code, const std::string& message) override {
    // The lowest failing rank speaks: (code != 0 ? rank : size) minimized over the ranks.
    int speaker = code != 0 ? rank_ : size_, first = 0;
    check(MPI_Allreduce(&speaker, &first, 1, MPI_INT, MPI_MIN, communicator_), "MPI_Allreduce");
    if (first == size_) return {0, std::string()};
    int header[2] = {code, static_cast<int>(message.size())};
    check(MPI_Bcast(header, 2, MPI_INT, first, communicator_), "MPI_Bcast");
    std::string text = rank_ == first ? message : std::string(header[1], ' ');
    check(MPI_Bcast(text.data(), header[1], MPI_CHAR, first, communicator_), "MPI_Bcast");
    return {header[0], text};
  }

  std::vector<int> partition(const std::vector<int>& offsets,
                             const std::vector<int>& adjacency) override {
    const PetscInt vertices = static_cast<PetscInt>(offsets.size()) - 1;
    // Each rank hands PT-Scotch a contiguous slice of the (replicated) graph.
    const PetscInt first = vertices * rank_ / size_, last = vertices * (rank_ + 1) / size_;
    PetscInt *rows = nullptr, *columns = nullptr;
    const PetscInt localEdges = offsets[last] - offsets[first];
    check(PetscMalloc1(last - first + 1, &rows), "PetscMalloc1");
    check(PetscMalloc1(std::max<PetscInt>(localEdges, 1), &columns), "PetscMalloc1");
    for (PetscInt v = first; v <= last; ++v) rows[v - first] = offsets[v] - offsets[first];
    for (PetscInt k = 0; k < localEdges; ++k) columns[k] = adjacency[offsets[first] + k];
    Mat graph = nullptr;  // takes ownership of rows and columns
    check(MatCreateMPIAdj(communicator_, last - first, vertices, rows, columns, nullptr, &graph),
          "MatCreateMPIAdj");
    MatPartitioning partitioner = nullptr;
    check(MatPartitioningCreate(communicator_, &partitioner), "MatPartitioningCreate");
    check(MatPartitioningSetAdjacency(partitioner, graph), "MatPartitioningSetAdjacency");
    check(MatPartitioningSetType(partitioner, MATPARTITIONINGPTSCOTCH), "MatPartitioningSetType");
    check(MatPartitioningSetFromOptions(partitioner), "MatPartitioningSetFromOptions");
    IS local = nullptr, all = nullptr;
    check(MatPartitioningApply(partitioner, &local), "MatPartitioningApply");
    check(ISAllGather(local, &all), "ISAllGather");
    const PetscInt* owners = nullptr;
    check(ISGetIndices(all, &owners), "ISGetIndices");
    std::vector<int> result(owners, owners + vertices);
    check(ISRestoreIndices(all, &owners), "ISRestoreIndices");
    ISDestroy(&all);
    ISDestroy(&local);
    MatPartitioningDestroy(&partitioner);
    MatDestroy(&graph);
    return result;
  }

  void useCollectiveFile(std::int64_t fileAccess, std::int64_t transfer) override {
    // The one HDF5 library of the process is the MPI build (CMakeLists.txt), so these are the
    // lists the results writer passes to H5Fcreate and H5Dwrite.
    check(H5Pset_fapl_mpio(fileAccess, communicator_, MPI_INFO_NULL) < 0 ? 1 : 0,
          "H5Pset_fapl_mpio");
    check(H5Pset_dxpl_mpio(transfer, H5FD_MPIO_COLLECTIVE) < 0 ? 1 : 0, "H5Pset_dxpl_mpio");
  }

  [[noreturn]] void abort(int code) override {
    MPI_Abort(communicator_, code);
    std::_Exit(code);  // not reached
  }

 private:
  MPI_Comm communicator_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
  double moved_ = 0;
};

}  // namespace

}  // namespace cc

extern "C" __attribute__((visibility("default"))) cc::ProcessGroup* covcontact_petsc_make_group() {
  return new cc::MpiGroup();
}
