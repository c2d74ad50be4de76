// Replaces the global operator new (a replaceable function of the standard library) with the
// same behaviour - malloc, the new-handler, std::bad_alloc - plus a record of the size that
// failed, so that an out-of-memory message can say how much was asked for. The default
// operator delete frees with free(), which matches. Not in sanitizer builds: ASan's own operator
// new checks new/delete pairing, which a malloc-based replacement would defeat.
#include "app/allocation_failure.hpp"

#include <fmt/format.h>
#include <sys/resource.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace {
std::atomic<std::size_t> failedRequest{0};
constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
}  // namespace

namespace cc::app {

std::size_t lastFailedAllocation() {
  return failedRequest.load(std::memory_order_relaxed);
}

std::string byteSize(double bytes) {
  if (bytes >= kGiB) return fmt::format("{:.2f} GiB", bytes / kGiB);
  if (bytes >= 1024.0 * 1024.0) return fmt::format("{:.1f} MiB", bytes / (1024.0 * 1024.0));
  return fmt::format("{:.0f} bytes", bytes);
}

std::string failedAllocationText() {
  const std::size_t bytes = lastFailedAllocation();
  if (bytes == 0) return "";
  return "; the allocation that failed asked for " + byteSize(static_cast<double>(bytes));
}

std::string addressSpaceLimitText() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return "";
  return "; the address space of the process is limited to " +
         byteSize(static_cast<double>(limit.rlim_cur)) + " (ulimit -v)";
}

}  // namespace cc::app

#if defined(__SANITIZE_ADDRESS__)
#define COVCONTACT_KEEP_OPERATOR_NEW 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define COVCONTACT_KEEP_OPERATOR_NEW 1
#endif
#endif

#ifndef COVCONTACT_KEEP_OPERATOR_NEW
namespace {
void* allocate(std::size_t size, std::size_t alignment) {
  if (size == 0) size = 1;
  for (;;) {
    void* memory =
        alignment <= alignof(std::max_align_t)
            ? std::malloc(size)
            : std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
    if (memory) return memory;
    // Recorded before the handler runs: it may free memory and let the next pass succeed.
    failedRequest.store(size, std::memory_order_relaxed);
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}
}  // namespace

// The other forms (arrays, nothrow) of libstdc++ call these two.
void* operator new(std::size_t size) {
  return allocate(size, 0);
}
void* operator new(std::size_t size, std::align_val_t alignment) {
  return allocate(size, static_cast<std::size_t>(alignment));
}
#endif
