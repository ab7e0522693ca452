#pragma once
// Scaling tests (issue 37): the work a job counts (engine/core/work_counter.h)
// at size n and at 4n. Linear work grows ~4x, n log n a little more, n^2
// ~16x; a count, unlike wall-clock time, does not depend on the machine.
#include <cstddef>
#include <cstdint>
#include <functional>

#include <gtest/gtest.h>

#include "engine/core/work_counter.h"

namespace testing_support {

inline uint64_t workOf(const std::function<void()>& job) {
  eng::resetWorkCount();
  job();
  return eng::workCount();
}

// Runs job(n) and job(4n); expects the larger to count between 3x (the work
// grows with the input: the count measures something) and maxRatio x.
inline void expectLinearWork(const std::function<void(size_t)>& job, size_t n, double maxRatio = 5.0) {
  const uint64_t small = workOf([&] { job(n); });
  const uint64_t large = workOf([&] { job(4 * n); });
  ASSERT_GT(small, 0u) << "the job counted no work: nothing was measured";
  EXPECT_LE(double(large), maxRatio * double(small))
      << "work at n = " << n << ": " << small << ", at 4n: " << large << " (linear ~4x, quadratic ~16x)";
  EXPECT_GE(double(large), 3.0 * double(small))
      << "work at n = " << n << ": " << small << ", at 4n: " << large << ": the input did not grow the work";
}

}  // namespace testing_support
