#include "torrance/bsdfs/glossy_bsdf.h"

namespace torrance {

GlossyBsdf::GlossyBsdf(const Vec3& color, float roughness)
    : color_(glm::clamp(color, Vec3(0.0f), Vec3(1.0f))) {
  const float r = std::isfinite(roughness) ? clamp01(roughness) : 0.0f;
  alpha_ = r * r;
}

LobeEval GlossyBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f || has_delta()) return {};
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return {};
  const float g = ggx::smith_G1(wo.z, alpha_) * ggx::smith_G1(wi.z, alpha_);
  LobeEval f;
  f.glossy = color_ * (ggx::D(h, alpha_) * g / (4.0f * wo.z));
  return f;
}

float GlossyBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f || has_delta()) return 0.0f;
  Vec3 h;
  return ggx::reflection_half(wo, wi, h) ? ggx::reflected_pdf(wo, h, alpha_) : 0.0f;
}

BsdfSample GlossyBsdf::sample(const Vec3& wo, float /*u_lobe*/, const Vec2& u) const {
  BsdfSample s;
  if (wo.z <= 0.0f) return s;
  if (has_delta()) {
    s.wi = Vec3(-wo.x, -wo.y, wo.z);
    s.weight = color_;
    s.is_delta = true;
    return s;
  }
  s.wi = ggx::reflect(wo, ggx::sample_visible_normal(wo, alpha_, u));
  if (s.wi.z <= 0.0f) return BsdfSample{};
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f)) return BsdfSample{};
  s.weight = eval(wo, s.wi) / s.pdf;
  return s;
}

}  // namespace torrance
