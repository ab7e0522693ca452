#include "tests/common/allocation_counter.h"

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

namespace {

std::atomic<uint64_t> gCount{0};
std::atomic<uint64_t> gBytes{0};

constexpr std::align_val_t kDefaultAlign{alignof(std::max_align_t)};

// nullptr when out of memory (the nothrow forms); the throwing forms turn that into bad_alloc.
void* tryAllocate(std::size_t size, std::align_val_t align = kDefaultAlign) noexcept {
  gCount.fetch_add(1, std::memory_order_relaxed);
  gBytes.fetch_add(size, std::memory_order_relaxed);
  const std::size_t a = static_cast<std::size_t>(align);
  return a <= alignof(std::max_align_t) ? std::malloc(size ? size : 1)
                                        : std::aligned_alloc(a, (size + a - 1) / a * a);
}

void* allocate(std::size_t size, std::align_val_t align = kDefaultAlign) {
  void* p = tryAllocate(size, align);
  if (!p) throw std::bad_alloc();
  return p;
}

}  // namespace

namespace testing_support {
uint64_t allocationCount() { return gCount.load(std::memory_order_relaxed); }
uint64_t allocatedBytes() { return gBytes.load(std::memory_order_relaxed); }
}  // namespace testing_support

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, std::align_val_t align) { return allocate(size, align); }
void* operator new[](std::size_t size, std::align_val_t align) { return allocate(size, align); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return tryAllocate(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return tryAllocate(size); }
void* operator new(std::size_t size, std::align_val_t align, const std::nothrow_t&) noexcept {
  return tryAllocate(size, align);
}
void* operator new[](std::size_t size, std::align_val_t align, const std::nothrow_t&) noexcept {
  return tryAllocate(size, align);
}
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
