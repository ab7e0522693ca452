#pragma once
// FNV-1a, 64 bits, over bytes: a cache key or a change detector (did a
// frame's inputs change?), not a checksum against tampering.
#include <cstdint>
#include <span>
#include <string_view>
#include <type_traits>

namespace eng {

struct Fnv1a {
  uint64_t h = 1469598103934665603ull;
  void add(std::string_view bytes) {
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  }
  // The object representation of trivially copyable values (no padding
  // bytes in them, or the key would follow garbage).
  template <class T>
  void addValues(std::span<const T> values) {
    static_assert(std::is_trivially_copyable_v<T>);
    add(std::string_view(reinterpret_cast<const char*>(values.data()), values.size_bytes()));
  }
  template <class T>
  void addValue(const T& value) {
    addValues(std::span<const T>(&value, 1));
  }
};

}  // namespace eng
