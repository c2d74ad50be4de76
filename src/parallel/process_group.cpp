// The one-process group and the choice between it and the MPI group of the PETSc plugin.
#include "parallel/process_group.hpp"

#include <cstdlib>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "solver/petsc_loader.hpp"

namespace cc {

namespace {

class SingleProcess final : public ProcessGroup {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  void sum(double*, std::size_t) override {}
  int maximum(int value) override { return value; }
  std::pair<int, std::string> agree(int code, const std::string& message) override {
    return {code, code != 0 ? message : std::string()};
  }
  std::vector<int> partition(const std::vector<int>& offsets, const std::vector<int>&) override {
    return std::vector<int>(offsets.empty() ? 0 : offsets.size() - 1, 0);
  }
  void useCollectiveFile(std::int64_t, std::int64_t) override {
    throw std::logic_error("useCollectiveFile: a run on one process writes without MPI-IO");
  }
  [[noreturn]] void abort(int code) override { std::exit(code); }
};

}  // namespace

ProcessGroup& processGroup() {
  static std::once_flag once;
  static std::unique_ptr<ProcessGroup> group;
  std::call_once(once, [] {
    if (launchedProcesses() > 1) {
      using MakeGroup = ProcessGroup* (*)();
      auto make = reinterpret_cast<MakeGroup>(petscPluginEntry("covcontact_petsc_make_group"));
      group.reset(make());
    } else {
      group = std::make_unique<SingleProcess>();
    }
  });
  return *group;
}

}  // namespace cc
