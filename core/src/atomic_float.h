// Adding to a float that other threads add to at the same time (the guide's recording).
#pragma once

namespace torrance {

inline void atomic_add_float(float& target, float value) {
  float expected;
  __atomic_load(&target, &expected, __ATOMIC_RELAXED);
  float desired = expected + value;
  while (!__atomic_compare_exchange(&target, &expected, &desired, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED))
    desired = expected + value;
}

}  // namespace torrance
