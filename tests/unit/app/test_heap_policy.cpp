// The heap policy (src/app/heap_policy.hpp): a small model keeps freed blocks of a few MiB in
// the heap for the next factorization; from kReturnFreedMemoryFrom equations on, such blocks are
// mapped and returned to the system again when freed. Observed through glibc's mallinfo2: the
// count of mmap-ed blocks while a 4 MiB block is held.
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdlib>

#include "app/heap_policy.hpp"

namespace {

// Whether a 4 MiB block is served by its own mapping (as glibc's defaults do) or by the heap.
bool fourMebibytesMapped() {
  const std::size_t before = mallinfo2().hblks;
  void* volatile block = std::malloc(4 << 20);  // volatile: the pair is not optimized away
  const bool mapped = mallinfo2().hblks > before;
  std::free(block);
  return mapped;
}

}  // namespace

// Each case in a child process of its own (gtest's threadsafe death-test style re-executes the
// test binary), whose heap holds no freed 4 MiB chunk that malloc could reuse whatever the policy.
[[noreturn]] void exitWithMapping(std::size_t freeEquations) {
  cc::app::keepFreedMemory();
  cc::app::chooseHeapPolicy(freeEquations);
  std::_Exit(fourMebibytesMapped() ? 1 : 0);
}

TEST(HeapPolicy, ASmallModelKeepsFactorizationSizedBlocksInTheHeap) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(exitWithMapping(cc::app::kReturnFreedMemoryFrom - 1), testing::ExitedWithCode(0), "");
}

TEST(HeapPolicy, ALargeModelMapsThemAndSoReturnsThemWhenFreed) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(exitWithMapping(cc::app::kReturnFreedMemoryFrom), testing::ExitedWithCode(1), "");
}
