#include "torrance/bsdfs/principled_sheen.h"

namespace torrance {

namespace {
constexpr float kClosureWeightCutoff = 1e-5f;  // Cycles' CLOSURE_WEIGHT_CUTOFF
}

SheenV1::SheenV1(float sheen, float tint, const Vec3& base, float diffuse_weight) {
  const float s = std::isfinite(sheen) ? sheen : 0.0f;
  if (!(s > kClosureWeightCutoff) || !(diffuse_weight > kClosureWeightCutoff)) return;
  const float lum = luminance(base);
  const Vec3 hue = lum > 0.0f ? base / lum : Vec3(1.0f);
  const float t = std::isfinite(tint) ? clamp01(tint) : 0.0f;
  color_ = s * diffuse_weight * glm::mix(Vec3(1.0f), hue, t);
  active_ = true;
}

float SheenV1::estimate(float cos_o) const {
  const float c = clamp01(cos_o);
  return (color_.r + color_.g + color_.b) / 3.0f * std::max(schlick_weight(c) * c, 0.01f);
}

SheenV2::SheenV2(float weight, float roughness, const Vec3& tint) {
  const float w = std::isfinite(weight) ? std::max(weight, 0.0f) : 0.0f;
  if (!(w > kClosureWeightCutoff)) return;
  const Vec3 color = w * glm::max(is_finite(tint) ? tint : Vec3(0.0f), Vec3(0.0f));
  lobe_ = SheenBsdf(color, std::isfinite(roughness) ? clamp01(roughness) : 0.0f);
  active_ = max_component(color) > 0.0f;
}

}  // namespace torrance
