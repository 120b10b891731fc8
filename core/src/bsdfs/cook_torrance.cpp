#include "torrance/bsdfs/cook_torrance.h"

namespace torrance {

CookTorranceBsdf::CookTorranceBsdf(const Material& m) {
  const Vec3 base = glm::clamp(m.base_color, Vec3(0.0f), Vec3(1.0f));
  const float metallic = clamp01(m.metallic);
  const float roughness = clamp01(m.roughness);
  const float dielectric_f0 = 0.08f * std::max(m.specular, 0.0f);
  diffuse_color_ = (1.0f - metallic) * base;
  f0_ = glm::clamp(glm::mix(Vec3(dielectric_f0), base, metallic), Vec3(0.0f), Vec3(1.0f));
  alpha_ = roughness * roughness;
  shape_ = ggx::Shape(alpha_);
  k_ = sqr(alpha_ + 1.0f) / 8.0f;
}

Vec3 CookTorranceBsdf::fresnel(float cos_theta) const {
  const float m = 1.0f - clamp01(cos_theta);
  const float m5 = (m * m) * (m * m) * m;
  return f0_ + (Vec3(1.0f) - f0_) * m5;
}

float CookTorranceBsdf::geometry_G1(float cos_theta) const {
  if (cos_theta <= 0.0f) return 0.0f;
  return cos_theta / (cos_theta * (1.0f - k_) + k_);
}

float CookTorranceBsdf::specular_probability(const Vec3& wo) const {
  const float spec = luminance(fresnel(wo.z));
  const float diff = luminance(diffuse_color_) * (1.0f - spec);
  return lobe_mixture::specular_probability(spec, diff);
}

CookTorranceBsdf::View CookTorranceBsdf::geometry(const Vec3& wo) const {
  View v;
  lobe_mixture::prepare(v, wo, shape_);
  v.geometry_o = geometry_G1(wo.z);
  return v;
}

CookTorranceBsdf::View CookTorranceBsdf::at(const Vec3& wo) const {
  View v = geometry(wo);
  v.p_spec = specular_probability(wo);
  return v;
}

LobeEval CookTorranceBsdf::eval_lobes(const View& v, const Vec3& wi) const {
  const Vec3& wo = v.wo;
  if (wo.z <= 0.0f || wi.z <= 0.0f) return {};
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return {};
  const Vec3 F = fresnel(glm::dot(wi, h));
  LobeEval f_cos;
  f_cos.diffuse = (Vec3(1.0f) - F) * diffuse_color_ * (kInvPi * wi.z);
  if (!has_delta()) {
    // D F G / (4 cos_o cos_i) * cos_i; G1(wo)/cos_o stays bounded (<= 1/k) at grazing wo.
    const float dg = ggx::D(h, alpha_) * v.geometry_o * geometry_G1(wi.z) / v.four_cos_o;
    f_cos.glossy = F * dg;
  }
  return f_cos;
}

}  // namespace torrance
