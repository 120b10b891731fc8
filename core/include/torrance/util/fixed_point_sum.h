// Sums that threads add to at the same time and that come out the same whatever order the
// additions happen in (the guide's recording): non-negative values in 64-bit fixed point, whose
// integer additions commute, where float additions round differently in each order -- and a
// guide learned from differently rounded sums samples other directions, so the same seed would
// give another image. A sum saturates at its largest value: with non-negative terms min(total,
// max) is also independent of the order.
#pragma once

#include <cstdint>
#include <limits>

namespace torrance {

// 2^FractionBits fixed-point units per 1: the resolution is 2^-(FractionBits + 1) (each term
// rounds to nearest), the largest sum 1.8e19 / 2^FractionBits.
template <int FractionBits>
struct FixedPointSum {
  static_assert(FractionBits >= 0 && FractionBits < 63, "a fraction that leaves room for the integer part");
  static constexpr double Scale = double(uint64_t(1) << FractionBits);
  static constexpr uint64_t kMax = std::numeric_limits<uint64_t>::max();

  // Thread-safe. value >= 0 and finite (others are the caller's bug; NaN adds nothing).
  void add(float value) {
    const double scaled = double(value) * Scale + 0.5;
    if (!(scaled >= 1.0)) return;
    const uint64_t term = scaled >= 1.8e19 ? kMax : uint64_t(scaled);
    uint64_t old = __atomic_load_n(&units, __ATOMIC_RELAXED);
    uint64_t sum;
    do {
      sum = old > kMax - term ? kMax : old + term;
    } while (!__atomic_compare_exchange_n(&units, &old, sum, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED));
  }
  double value() const { return double(units) / Scale; }

  uint64_t units = 0;
};

}  // namespace torrance
