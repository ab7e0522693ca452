#pragma once
// Heap allocations made by this process so far. A binary that links the
// `allocation_counter` library (tests/CMakeLists.txt) replaces every form of
// the global operator new and delete, nothrow ones included (a form left out
// would come from the runtime or the sanitizer's allocator and be freed
// here), with ones that count calls and bytes. Tests and benchmarks read the
// counts around the code under watch: the runtime's per-frame paths must
// make no allocation. Kept out of test_support, which every test links.
#include <cstdint>

#include "engine/core/work_counter.h"

namespace testing_support {

uint64_t allocationCount();
uint64_t allocatedBytes();

// Runs `job`, counting its heap allocations as work (eng::countWork): a
// scaling test (work_scaling.h) then also sees the work of code that counts
// nothing itself, such as tinygltf's parse.
template <class Job>
void countAllocationsAsWork(Job&& job) {
  const uint64_t before = allocationCount();
  job();
  eng::countWork(allocationCount() - before);
}

}  // namespace testing_support
