// What an out-of-memory message can say beyond std::bad_alloc, which says nothing: the size of
// the request that failed (recorded by this module's replacement of the global operator new)
// and the address-space limit the process runs under (ulimit -v), if any.
#pragma once

#include <cstddef>
#include <string>

namespace cc::app {

// Bytes of the last operator new request that failed; 0 when none was recorded (Eigen's dense
// storage and the C libraries allocate with malloc, whose failures are not seen here, and
// sanitizer builds keep the sanitizer's own operator new).
std::size_t lastFailedAllocation();

// "1104 bytes", "12.5 MiB", "1.20 GiB".
std::string byteSize(double bytes);

// "; the allocation that failed asked for 1.20 GiB", or "" when not known.
std::string failedAllocationText();
// "; the address space of the process is limited to 1.50 GiB (ulimit -v)", or "" without a limit.
std::string addressSpaceLimitText();

}  // namespace cc::app
