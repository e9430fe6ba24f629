// Counts heap allocations made by this process: every operator new / new[] (all builds) and, outside
// sanitizer builds, every malloc / calloc / realloc / aligned_alloc / posix_memalign too. Link
// alloc_counter.cpp into a test to use it ("no allocation after init" proofs).
#pragma once

#include <cstdint>

namespace visnav::test {

/// Allocations counted since the process started (every thread, Cyclone DDS's background threads included).
std::uint64_t allocationCount();
/// Allocations made by the calling thread since it started: the cycle's own, without other threads' noise.
std::uint64_t threadAllocationCount();
/// True when malloc-family calls are counted as well as operator new (not under ASan, which owns malloc).
bool countsMalloc();

}  // namespace visnav::test
