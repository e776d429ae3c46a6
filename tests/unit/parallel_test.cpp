// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/util/parallel.h"

#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <xmmintrin.h>

#include <atomic>

namespace qs {
namespace {

// The flush-to-zero and denormals-are-zero bits of MXCSR.
constexpr unsigned kZeroModes = 0x8040;

// Whether every task of a parallel_for_as_here() over 4,096 indices (both forms) ran with
// the calling thread's zero modes.
bool tasks_compute_as_here() {
  const unsigned here = _mm_getcsr() & kZeroModes;
  std::atomic<int> other{0};
  parallel_for_as_here(0, 4096, [&](int) { other += (_mm_getcsr() & kZeroModes) != here; });
  parallel_for_as_here(tbb::blocked_range<int>(0, 4096, 16), [&](const tbb::blocked_range<int>&) {
    other += (_mm_getcsr() & kZeroModes) != here;
  });
  return other == 0;
}

TEST(Parallel, tasks_compute_with_the_callers_floating_point_settings) {
  // Embree's BVH build turns both modes on, and TBB's tasks took the settings of whichever
  // context came first: automatic halting then judged faces on one setting and the loop on
  // the other (bench/RESULTS.md, "Floating-point settings in TBB's tasks").
  const unsigned saved = _mm_getcsr();
  _mm_setcsr(saved | kZeroModes);
  const bool with_modes = tasks_compute_as_here();
  _mm_setcsr(saved & ~kZeroModes);
  const bool without_modes = tasks_compute_as_here();
  _mm_setcsr(saved);
  EXPECT_TRUE(with_modes);
  EXPECT_TRUE(without_modes);
}

}  // namespace
}  // namespace qs
