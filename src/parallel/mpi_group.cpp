// The ProcessGroup of a run on several processes: MPI_COMM_WORLD (PETSC_COMM_WORLD), with the
// mesh partitioned by Scotch on rank 0. Part of the PETSc plugin: the only code of the program
// that calls MPI.
#include <fmt/format.h>
#include <hdf5.h>
#include <mpi.h>
#include <petscsys.h>

#include <algorithm>
#include <cstdio>  // before scotch.h, which uses FILE
#include <cstdlib>
#include <stdexcept>
#include <vector>

extern "C" {
#include <scotch.h>
}

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

  // Every rank holds the whole graph, so rank 0 partitions it with sequential Scotch and
  // broadcasts the owners. Not PT-Scotch through PETSc's MatPartitioning, as before the
  // thirty-second session: its threads made the partition differ from run to run (3 different
  // partitions of the 20 k scaling deck's graph in 10 runs, 3 to 5 with its random generator
  // reset or the whole graph on one process), and with it the summation order, the AMG
  // hierarchy and the iteration counts. Scotch's context makes the sequential partition
  // deterministic (a fixed random seed, no thread-order dependence): the same deck on the same
  // number of processes is partitioned the same way in every run.
  std::vector<int> partition(const std::vector<int>& offsets,
                             const std::vector<int>& adjacency) override {
    const int vertices = static_cast<int>(offsets.size()) - 1;
    std::vector<int> owners(static_cast<std::size_t>(vertices), 0);
    int failed = 0;
    if (rank_ == 0) failed = scotchPartition(offsets, adjacency, owners) ? 0 : 1;
    check(MPI_Bcast(&failed, 1, MPI_INT, 0, communicator_), "MPI_Bcast");
    if (failed) throw std::runtime_error("Scotch could not partition the mesh's node graph");
    check(MPI_Bcast(owners.data(), vertices, MPI_INT, 0, communicator_), "MPI_Bcast");
    return owners;
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
  // The graph (CSR, 0-based) cut into size_ parts by Scotch's default strategy with PETSc's
  // former imbalance of 1 %; false when Scotch reports an error (it prints it).
  bool scotchPartition(const std::vector<int>& offsets, const std::vector<int>& adjacency,
                       std::vector<int>& owners) const {
    static_assert(sizeof(SCOTCH_Num) == sizeof(int), "libscotch-dev's SCOTCH_Num is int");
    const SCOTCH_Num vertices = static_cast<SCOTCH_Num>(offsets.size()) - 1;
    SCOTCH_Graph graph, boundGraph;
    SCOTCH_Strat strategy;
    SCOTCH_Context context;
    SCOTCH_graphInit(&graph);
    SCOTCH_graphInit(&boundGraph);
    SCOTCH_stratInit(&strategy);
    SCOTCH_contextInit(&context);
    bool ok = SCOTCH_graphBuild(&graph, 0, vertices, offsets.data(), nullptr, nullptr, nullptr,
                                offsets[static_cast<std::size_t>(vertices)], adjacency.data(),
                                nullptr) == 0 &&
              SCOTCH_stratGraphMapBuild(&strategy, SCOTCH_STRATDEFAULT, size_, 0.01) == 0 &&
              SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMDETERMINISTIC, 1) == 0 &&
              SCOTCH_contextOptionSetNum(&context, SCOTCH_OPTIONNUMRANDOMFIXEDSEED, 1) == 0;
    if (ok) {
      SCOTCH_contextRandomSeed(&context, 1);
      ok = SCOTCH_contextBindGraph(&context, &graph, &boundGraph) == 0 &&
           SCOTCH_graphPart(&boundGraph, size_, &strategy, owners.data()) == 0;
    }
    SCOTCH_graphExit(&boundGraph);
    SCOTCH_contextExit(&context);
    SCOTCH_stratExit(&strategy);
    SCOTCH_graphExit(&graph);
    return ok;
  }

  MPI_Comm communicator_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
  double moved_ = 0;
};

}  // namespace

}  // namespace cc

extern "C" __attribute__((visibility("default"))) cc::ProcessGroup* covcontact_petsc_make_group() {
  return new cc::MpiGroup();
}
