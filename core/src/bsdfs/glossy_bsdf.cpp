#include "torrance/bsdfs/glossy_bsdf.h"

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
                       bool cycles4, bool multiscatter, MicrofacetDistribution distribution)
    : color_(glm::clamp(color, Vec3(0.0f), Vec3(1.0f))),
      lobe_(lobe_shape(roughness, anisotropy, tangent, rotation), distribution),
      cycles4_(cycles4) {
  const ggx::Shape& shape = lobe_.shape();
  if (cycles4 && multiscatter && distribution == MicrofacetDistribution::GGX)
    multiscatter_roughness_ = shape.anisotropic() ? std::sqrt(std::sqrt(shape.alpha_x() * shape.alpha_y()))
                                                  : (std::isfinite(roughness) ? clamp01(roughness) : 0.0f);
}

LobeEval GlossyBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f || has_delta()) return {};
  LobeEval f;
  if (lobe_.ashikhmin_shirley()) {
    f.glossy = color_ * lobe_.ashikhmin_shirley_eval(wo, wi);
    return f;
  }
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return {};
  const float g = cycles4_ ? 1.0f / (1.0f + lobe_.lambda(wo) + lobe_.lambda(wi)) : lobe_.G1(wo) * lobe_.G1(wi);
  f.glossy = color_ * (lobe_.D(h) * g / (4.0f * wo.z));
  if (multiscatter_roughness_ >= 0.0f) {
    const float e = std::max(ggx_tables::albedo(multiscatter_roughness_, wo.z), 1e-3f);
    f.glossy *= multiscatter::scale(color_, e, ggx_tables::average_albedo(multiscatter_roughness_));
  }
  return f;
}

float GlossyBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  return has_delta() ? 0.0f : lobe_.reflection_pdf(wo, wi);
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
  s.wi = lobe_.sample_reflection(wo, u);
  if (s.wi.z <= 0.0f) return BsdfSample{};
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f)) return BsdfSample{};
  s.weight = eval(wo, s.wi) / s.pdf;
  return s;
}

}  // namespace torrance
