#pragma once
// Heap allocations made by this process so far: every benchmark binary that
// links allocation_counter.cpp replaces the global operator new with one that
// counts (calls and bytes). Benchmarks read it around their loop to report
// allocations per operation (the runtime's per-frame paths must make none).
#include <cstdint>

namespace bench {

uint64_t allocationCount();
uint64_t allocatedBytes();

}  // namespace bench
