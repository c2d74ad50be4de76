// How the engine's heap keeps or returns freed memory, by model size. Small models reuse the
// pages UMFPACK frees after each factorization (keeping them halved the CPU of example 6.1);
// large ones return freed memory to the system, where it would only add to the peak.
#pragma once

#include <cstddef>

#include "solver/linear_solver.hpp"

namespace cc::app {

// At the start of main: serve blocks up to 32 MiB from the heap and keep freed heap memory.
void keepFreedMemory();

// Once the model is built: from kReturnFreedMemoryFrom free equations on, glibc's own thresholds
// (128 KiB) again, so that freed memory goes back to the system.
inline constexpr std::size_t kReturnFreedMemoryFrom = kMemoryBoundSystemFrom;
void chooseHeapPolicy(std::size_t freeEquations);

}  // namespace cc::app
