#include "integrator/first_hit_passes.h"

#include <algorithm>
#include <cmath>

namespace torrance {

float mist_clearance(const PathContext& ctx, const Vec3& position) {
  const RenderSettings& s = ctx.settings;
  const Vec3 d = position - ctx.camera_position;
  const float distance = ctx.orthographic ? std::abs(glm::dot(d, ctx.camera_forward)) : glm::length(d);
  const float inv_depth = s.mist_depth > 0.0f ? 1.0f / s.mist_depth : 0.0f;
  float mist = std::clamp((distance - s.mist_start) * inv_depth, 0.0f, 1.0f);
  if (s.mist_falloff == 2.0f) mist *= mist;
  else if (s.mist_falloff == 0.5f) mist = std::sqrt(mist);
  else if (s.mist_falloff != 1.0f) mist = std::pow(mist, s.mist_falloff);
  return 1.0f - mist;
}

Vec3 glossy_color(const Material& m) {
  if (m.glass_node) return m.base_color;
  constexpr float kCutoff = 1e-5f;  // CLOSURE_WEIGHT_CUTOFF
  const float metallic = std::clamp(m.metallic, 0.0f, 1.0f);
  const float glass = std::clamp(m.transmission, 0.0f, 1.0f) * (1.0f - metallic);
  const bool specular = 1.0f - glass > kCutoff && (m.specular > kCutoff || metallic > kCutoff);
  return Vec3((specular ? 1.0f - glass : 0.0f) + (glass > kCutoff ? glass : 0.0f) +
              (m.coat_weight > kCutoff ? 1.0f : 0.0f));
}

}  // namespace torrance
