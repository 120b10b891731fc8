#include "torrance/bsdfs/glossy_bsdf.h"

#include "torrance/bsdfs/beckmann.h"
#include "torrance/bsdfs/principled_coat.h"  // multiscatter::scale

#include <algorithm>

namespace torrance {

ggx::Shape GlossyBsdf::lobe_shape(float roughness, float anisotropy, const Vec3& tangent, float rotation) {
  const float r = std::isfinite(roughness) ? clamp01(roughness) : 0.0f;
  const float alpha = r * r;
  const float a = std::isfinite(anisotropy) ? std::clamp(anisotropy, -0.99f, 0.99f) : 0.0f;
  if (a == 0.0f) return ggx::Shape(alpha);
  const float alpha_x = std::min(a < 0.0f ? alpha / (1.0f + a) : alpha * (1.0f - a), 1.0f);
  const float alpha_y = std::min(a < 0.0f ? alpha * (1.0f + a) : alpha / (1.0f - a), 1.0f);
  const ggx::Shape shape(alpha_x, alpha_y, tangent, std::isfinite(rotation) ? kTwoPi * rotation : 0.0f);
  return shape.anisotropic() ? shape : ggx::Shape(alpha);  // no tangent: Cycles' isotropic lobe
}

GlossyBsdf::GlossyBsdf(const Vec3& color, float roughness, float anisotropy, const Vec3& tangent, float rotation,
                       bool cycles4, bool multiscatter, bool beckmann)
    : color_(glm::clamp(color, Vec3(0.0f), Vec3(1.0f))),
      shape_(lobe_shape(roughness, anisotropy, tangent, rotation)),
      cycles4_(cycles4),
      beckmann_(beckmann) {
  if (cycles4 && multiscatter && !beckmann)
    multiscatter_roughness_ = shape_.anisotropic() ? std::sqrt(std::sqrt(shape_.alpha_x() * shape_.alpha_y()))
                                                   : (std::isfinite(roughness) ? clamp01(roughness) : 0.0f);
}

float GlossyBsdf::D(const Vec3& h) const {
  return beckmann_ ? beckmann::D_aniso(shape_.to_lobe(h), shape_.alpha_x(), shape_.alpha_y()) : shape_.D(h);
}

float GlossyBsdf::lambda(const Vec3& w) const {
  return beckmann_ ? beckmann::lambda_aniso(shape_.to_lobe(w), shape_.alpha_x(), shape_.alpha_y()) : shape_.lambda(w);
}

float GlossyBsdf::visible_g1(const Vec3& wo) const {
  if (!beckmann_) return shape_.G1(wo);
  return 1.0f / (1.0f + beckmann::lambda_exact_aniso(shape_.to_lobe(wo), shape_.alpha_x(), shape_.alpha_y()));
}

Vec3 GlossyBsdf::sample_visible_normal(const Vec3& wo, const Vec2& u) const {
  if (!beckmann_) return shape_.sample_visible_normal(wo, u);
  return shape_.from_lobe(
      beckmann::sample_visible_normal_aniso(shape_.to_lobe(wo), shape_.alpha_x(), shape_.alpha_y(), u));
}

LobeEval GlossyBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f || has_delta()) return {};
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return {};
  float g;
  if (cycles4_)
    g = 1.0f / (1.0f + lambda(wo) + lambda(wi));
  else if (beckmann_)
    g = 1.0f / ((1.0f + lambda(wo)) * (1.0f + lambda(wi)));  // Cycles 3.x's G1(wo) G1(wi) of its fit
  else
    g = shape_.G1(wo) * shape_.G1(wi);
  LobeEval f;
  f.glossy = color_ * (D(h) * g / (4.0f * wo.z));
  if (multiscatter_roughness_ >= 0.0f) {
    const float e = std::max(ggx_tables::albedo(multiscatter_roughness_, wo.z), 1e-3f);
    f.glossy *= multiscatter::scale(color_, e, ggx_tables::average_albedo(multiscatter_roughness_));
  }
  return f;
}

float GlossyBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  if (has_delta() || wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return 0.0f;
  return visible_g1(wo) * D(h) / (4.0f * wo.z);
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
  s.wi = ggx::reflect(wo, sample_visible_normal(wo, u));
  if (s.wi.z <= 0.0f) return BsdfSample{};
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f)) return BsdfSample{};
  s.weight = eval(wo, s.wi) / s.pdf;
  return s;
}

}  // namespace torrance
