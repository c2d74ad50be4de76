// The heap policy of the engine (heap_policy.hpp says what it owns).
#include "app/heap_policy.hpp"

#include <malloc.h>

namespace cc::app {

// UMFPACK allocates its numeric workspace (several MiB at 4 k equations) at every
// factorization and frees it afterwards. With glibc's defaults such blocks are mmap-ed and
// returned to the kernel each time, so every factorization page-faults and clears them anew:
// on example 6.1 (40 x 10 block, 4 k equations, one thread) that was ~40% of the CPU time
// (perf: page faults 19%, memset 9%, umfdl_mem_alloc_tail_block 10%). Serving blocks up to
// 32 MiB (glibc's largest mmap threshold) from the heap and keeping up to 1 GiB of freed heap
// lets the next factorization reuse the same pages: task-clock 3.28 -> 1.63 s, page faults
// 87 928 -> 6 350 for 11 steps (docs/performance/solvers.md). Larger factors stay mmap-ed;
// their cost is arithmetic, not allocation.
void keepFreedMemory() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_TOP_PAD, 64 << 20);
}

// At 232 k equations (example 6.1 refined, CHOLMOD and UMFPACK, one thread) the kept heap
// made the peak RSS 2334 MiB; with glibc's thresholds from the start it was 2.15 GiB at the
// same CPU time (611 against 615 s, side by side), and with this switch after the model is
// built 2174 MiB: there the factorizations' arithmetic is the cost, not their allocations.
void chooseHeapPolicy(std::size_t freeEquations) {
  if (freeEquations < kReturnFreedMemoryFrom) return;
  constexpr int kGlibcDefault = 128 * 1024;
  mallopt(M_MMAP_THRESHOLD, kGlibcDefault);
  mallopt(M_TRIM_THRESHOLD, kGlibcDefault);
  mallopt(M_TOP_PAD, kGlibcDefault);
  malloc_trim(0);
}

}  // namespace cc::app
