// Helpers shared by the core tests.
#pragma once

#include "torrance/bsdf.h"
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

// Every BRDF model, and its name as the module spells it.
inline constexpr BrdfModel kAllModels[] = {BrdfModel::Paper, BrdfModel::Principled, BrdfModel::PrincipledV2};
inline const char* model_name(BrdfModel m) {
  return m == BrdfModel::Paper ? "PAPER" : m == BrdfModel::Principled ? "PRINCIPLED" : "PRINCIPLED_V2";
}

}  // namespace torrance::test
