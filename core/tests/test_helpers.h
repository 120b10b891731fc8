// Helpers shared by the core tests.
#pragma once

#include "torrance/math.h"
#include "torrance/sampling.h"

namespace torrance::test {

// A unit direction in the upper hemisphere with the given cosine and azimuth.
inline Vec3 direction(float cos_theta, float phi) {
  const float s = safe_sqrt(1.0f - cos_theta * cos_theta);
  return Vec3(s * std::cos(phi), s * std::sin(phi), cos_theta);
}

// Uniformly distributed unit vector on the sphere.
inline Vec3 uniform_sphere(Rng& rng) {
  const float z = 1.0f - 2.0f * rng.next_1d();
  return direction(z, kTwoPi * rng.next_1d());
}

}  // namespace torrance::test
