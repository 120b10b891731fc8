#include "torrance/subsurface/subsurface_lobe.h"

#include <algorithm>
#include <limits>

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
  s.plain_radius = s.van_de_hulst = m.subsurface_van_de_hulst && !m.subsurface_skin;
  // Cycles 5.x allows a negative anisotropy (its legacy walks take d'Eon's mapping for it) and up
  // to 0.99 in its Random Walk; 3.x/4.x clamp to [0, 0.9].
  const float g_min = m.subsurface_after_diffuse ? -0.99f : 0.0f;
  s.anisotropy = std::clamp(m.subsurface_anisotropy, g_min, s.van_de_hulst ? 0.99f : 0.9f);
  if (s.anisotropy < 0.0f) s.van_de_hulst = true;
  s.fixed_radius = m.subsurface_fixed_radius && !m.subsurface_skin && !m.subsurface_van_de_hulst;
  s.burley = m.subsurface_burley && !m.subsurface_skin;
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

float min_walk_radius(const Material& m, const WalkState& s) {
  // Cycles 5.x keeps Christensen-Burley's fallback after a diffuse bounce.
  const bool after_diffuse = m.subsurface_after_diffuse && !m.subsurface_burley;
  if (!s.walkable || (s.diffuse_ancestor && !after_diffuse)) return std::numeric_limits<float>::infinity();
  return std::max(m.subsurface_min_footprint * s.footprint, kMinSubsurfaceRadius);
}

Material walked_only(const Material& m, float min_radius) {
  Material w = m;
  for (int c = 0; c < 3; ++c)
    if (!(w.subsurface_radius[c] >= min_radius)) w.subsurface_radius[c] = 0.0f;
  return w;
}

SubsurfaceLobe principled_v2_subsurface(const Material& m, float eta, int component, float mix_weight) {
  if (!(m.subsurface > kWeightCutoff)) return {};
  const float diffuse_weight = (1.0f - clamp01(m.metallic)) * (1.0f - clamp01(m.transmission));
  if (!(diffuse_weight > kWeightCutoff)) return {};
  const Vec3 albedo = glm::clamp(m.base_color, Vec3(0.0f), Vec3(1.0f));
  // The weight's colour, Subsurface Weight and layers come from PrincipledV2Bsdf::subsurface_weight.
  SubsurfaceLobe s = lobe(Vec3(mix_weight), albedo, m.subsurface_radius, m);
  if (!m.subsurface_skin) {
    s.ior = std::clamp(eta, 1.01f, 3.8f);
    const float roughness = clamp01(m.roughness);
    s.entry_alpha = roughness * roughness;
  }
  s.layered_component = component;
  // The diffuse, specular, coat and sheen closures' Cycles sample weights, roughly.
  s.others = 0.25f + 3.0f * (1.0f - clamp01(m.subsurface)) * diffuse_weight * luminance(albedo);
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
