// A parallel pass over [0, n) that reports the first index where a check fails (issue 11: the
// checks and copies of a 10 M-triangle mesh on every core). Callers then throw the message
// for that index, so errors name the same element as a serial loop would.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cstddef>

namespace torrance {

struct NoBlockState {};

// Calls fails(i) for every i in [0, n) (in parallel; a block stops at its first failure) and
// returns the smallest i for which it returned true, or n when none did. A BlockState lives
// on the worker's stack while it runs a block (e.g. to set the thread's floating-point mode).
template <typename BlockState = NoBlockState, typename Fails>
size_t first_failure(size_t n, const Fails& fails) {
  std::atomic<size_t> first{n};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const tbb::blocked_range<size_t>& r) {
    [[maybe_unused]] BlockState state;
    for (size_t i = r.begin(); i != r.end(); ++i)
      if (fails(i)) {
        size_t seen = first.load();
        while (i < seen && !first.compare_exchange_weak(seen, i)) {
        }
        return;
      }
  });
  return first.load();
}

}  // namespace torrance
