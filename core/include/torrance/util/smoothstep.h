// Cycles' two smooth steps, 3t^2 - 2t^3 computed in two orders that round differently (each
// node uses the one its Cycles kernel does, so that the results are Cycles' to the bit).
#pragma once

namespace torrance {

// Cycles' smoothstep(e0, e1, x): 0 below e0, 1 from e1 on, between (3 - 2t) t^2 of
// t = (x - e0) / (e1 - e0); NaN stays NaN.
inline float smooth_step(float e0, float e1, float x) {
  if (x < e0) return 0.0f;
  if (x >= e1) return 1.0f;
  const float t = (x - e0) / (e1 - e0);
  return (3.0f - 2.0f * t) * (t * t);
}

// Cycles' smoothstepf(t) (the Brick and Gradient Textures'): 3 t^2 - 2 t^2 t, t not clamped.
inline float smooth_step_unclamped(float t) {
  const float t2 = t * t;
  return 3.0f * t2 - 2.0f * t2 * t;
}

}  // namespace torrance
