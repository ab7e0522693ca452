#pragma once
// A hash key for a mesh edge that is the same whichever way round the edge is
// walked: the smaller vertex index in the high 32 bits.
#include <cstdint>

namespace eng {

inline uint64_t undirectedEdgeKey(uint32_t a, uint32_t b) {
  return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a;
}

}  // namespace eng
