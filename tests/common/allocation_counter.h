#pragma once
// Heap allocations made by this process so far. A binary that links the
// `allocation_counter` library (tests/CMakeLists.txt) replaces every form of
// the global operator new and delete, nothrow ones included (a form left out
// would come from the runtime or the sanitizer's allocator and be freed
// here), with ones that count calls and bytes. Tests and benchmarks read the
// counts around the code under watch: the runtime's per-frame paths must
// make no allocation. Kept out of test_support, which every test links.
#include <cstdint>

namespace testing_support {

uint64_t allocationCount();
uint64_t allocatedBytes();

}  // namespace testing_support
