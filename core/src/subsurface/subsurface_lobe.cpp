#include "torrance/subsurface/subsurface_lobe.h"

#include <algorithm>

namespace torrance {

namespace {

// Cycles' cutoff below which a closure weight counts as none (CLOSURE_WEIGHT_CUTOFF).
constexpr float kWeightCutoff = 1e-5f;

Vec3 walked_channels(const Vec3& radius) {
  return Vec3(radius.x >= kMinSubsurfaceRadius, radius.y >= kMinSubsurfaceRadius, radius.z >= kMinSubsurfaceRadius);
}

SubsurfaceLobe lobe(const Vec3& weight, const Vec3& albedo, const Vec3& radius, const Material& m) {
  SubsurfaceLobe s;
  const Vec3 r = glm::max(radius, Vec3(0.0f));
  s.weight = glm::max(weight, Vec3(0.0f)) * walked_channels(r);
  s.albedo = glm::clamp(albedo, Vec3(0.0f), Vec3(1.0f));
  s.radius = r;
  s.ior = std::clamp(m.subsurface_ior, 1.01f, 3.8f);
  s.anisotropy = std::clamp(m.subsurface_anisotropy, 0.0f, 0.9f);
  s.fixed_radius = m.subsurface_fixed_radius && !m.subsurface_skin;
  s.entry_alpha = m.subsurface_skin ? 1.0f : std::min(m.subsurface_entry_alpha, 1.0f);
  s.entry_half_lambertian = m.subsurface_skin;
  return s;
}

}  // namespace

float SubsurfaceLobe::choice_probability() const {
  const float channels = float(int(weight.x > 0.0f) + int(weight.y > 0.0f) + int(weight.z > 0.0f));
  const float walk = (weight.x + weight.y + weight.z) / 3.0f * channels;
  return walk > 0.0f ? walk / (walk + others) : 0.0f;
}

Vec3 principled_subsurface_albedo(const Material& m) {
  return glm::mix(m.base_color, m.subsurface_color, m.subsurface);
}

SubsurfaceLobe principled_subsurface(const Material& m, float mix_weight) {
  if (!(m.subsurface > kWeightCutoff)) return {};
  const float diffuse_weight = (1.0f - clamp01(m.metallic)) * (1.0f - clamp01(m.transmission));
  if (!(diffuse_weight > kWeightCutoff)) return {};
  const Vec3 albedo = principled_subsurface_albedo(m);
  SubsurfaceLobe s = lobe(mix_weight * diffuse_weight * albedo, albedo, m.subsurface_radius * m.subsurface, m);
  s.exit_fresnel = true;
  s.others = 0.25f;  // the specular, retro-reflection, sheen and coat lobes: sampled 1 time in 4 or more
  return s;
}

SubsurfaceLobe node_subsurface(const Material& m, float mix_weight) {
  return lobe(mix_weight * m.base_color, m.base_color, m.subsurface_radius, m);
}

Vec3 principled_lambert_channels(const Material& m) {
  if (!(m.subsurface > kWeightCutoff)) return Vec3(1.0f);
  return Vec3(1.0f) - walked_channels(glm::max(m.subsurface_radius * m.subsurface, Vec3(0.0f)));
}

}  // namespace torrance
