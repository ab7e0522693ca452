#pragma once
// Work done where a file's size decides the work (a node placed, a name
// compared, a point tested, a morph entry packed), in those inner steps.
// Scaling tests read it at n and 4n and expect ~4x, not ~16x (issue 37):
// a count is exact where wall-clock time is noisy. thread_local, so tests
// running side by side do not mix; the increment is one add.
#include <cstdint>

namespace eng {

inline thread_local uint64_t tWorkCount = 0;

inline void countWork(uint64_t steps = 1) { tWorkCount += steps; }

// The steps counted on this thread since the last reset.
inline uint64_t workCount() { return tWorkCount; }
inline void resetWorkCount() { tWorkCount = 0; }

}  // namespace eng
