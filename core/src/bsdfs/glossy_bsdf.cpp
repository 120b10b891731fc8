#include "torrance/bsdfs/glossy_bsdf.h"

#include <algorithm>

namespace torrance {

GlossyBsdf::GlossyBsdf(const Vec3& color, float roughness, float anisotropy, const Vec3& tangent, float rotation)
    : color_(glm::clamp(color, Vec3(0.0f), Vec3(1.0f))) {
  const float r = std::isfinite(roughness) ? clamp01(roughness) : 0.0f;
  const float alpha = r * r;
  alpha_x_ = alpha_y_ = alpha;
  const float a = std::isfinite(anisotropy) ? std::clamp(anisotropy, -0.99f, 0.99f) : 0.0f;
  if (a == 0.0f || !is_finite(tangent) || !(glm::dot(tangent, tangent) > 0.0f)) return;
  anisotropic_ = true;
  tangent_ = tangent;
  rotation_ = std::isfinite(rotation) ? kTwoPi * rotation : 0.0f;
  alpha_x_ = std::min(a < 0.0f ? alpha / (1.0f + a) : alpha * (1.0f - a), 1.0f);
  alpha_y_ = std::min(a < 0.0f ? alpha * (1.0f + a) : alpha / (1.0f - a), 1.0f);
}

void GlossyBsdf::orient(const Frame& frame) {
  if (!anisotropic_) return;
  const Vec3 t = frame.to_local(tangent_);
  float c = 1.0f, s = 0.0f;
  if (const float len = std::sqrt(t.x * t.x + t.y * t.y); len > 1e-6f) c = t.x / len, s = t.y / len;
  const float cr = std::cos(rotation_), sr = std::sin(rotation_);
  cos_ = c * cr - s * sr;
  sin_ = s * cr + c * sr;
}

float GlossyBsdf::reflected_pdf(const Vec3& wo, const Vec3& h) const {
  return ggx::smith_G1_aniso(wo, alpha_x_, alpha_y_) * ggx::D_aniso(h, alpha_x_, alpha_y_) / (4.0f * wo.z);
}

LobeEval GlossyBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f || has_delta()) return {};
  LobeEval f;
  if (anisotropic_) {
    const Vec3 o = to_lobe(wo), i = to_lobe(wi);
    Vec3 h;
    if (!ggx::reflection_half(o, i, h)) return {};
    f.glossy = color_ * (reflected_pdf(o, h) * ggx::smith_G1_aniso(i, alpha_x_, alpha_y_));
    return f;
  }
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return {};
  const float g = ggx::smith_G1(wo.z, alpha_x_) * ggx::smith_G1(wi.z, alpha_x_);
  f.glossy = color_ * (ggx::D(h, alpha_x_) * g / (4.0f * wo.z));
  return f;
}

float GlossyBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f || has_delta()) return 0.0f;
  Vec3 h;
  if (anisotropic_) {
    const Vec3 o = to_lobe(wo);
    return ggx::reflection_half(o, to_lobe(wi), h) ? reflected_pdf(o, h) : 0.0f;
  }
  return ggx::reflection_half(wo, wi, h) ? ggx::reflected_pdf(wo, h, alpha_x_) : 0.0f;
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
  s.wi = anisotropic_
             ? from_lobe(ggx::reflect(to_lobe(wo), ggx::sample_visible_normal_aniso(to_lobe(wo), alpha_x_, alpha_y_, u)))
             : ggx::reflect(wo, ggx::sample_visible_normal(wo, alpha_x_, u));
  if (s.wi.z <= 0.0f) return BsdfSample{};
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f)) return BsdfSample{};
  s.weight = eval(wo, s.wi) / s.pdf;
  return s;
}

}  // namespace torrance
