#include "torrance/bsdfs/metallic_bsdf.h"

#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/principled_coat.h"  // multiscatter::scale

#include <algorithm>

namespace torrance {

MetallicBsdf::MetallicBsdf(bool conductor, const Vec3& first, const Vec3& second, float roughness, float anisotropy,
                           const Vec3& tangent, float rotation, bool multiscatter, const ThinFilm& film,
                           bool beckmann)
    : conductor_(conductor) {
  if (conductor) {
    n_ = glm::max(first, Vec3(0.0f));
    k_ = glm::max(second, Vec3(0.0f));
    f82_ = F82Tint::through(conductor_fresnel(1.0f, n_, k_), conductor_fresnel(1.0f / 7.0f, n_, k_));
    fss_ = glm::clamp(f82_.fss(), Vec3(0.0f), Vec3(1.0f));
  } else {
    f82_ = F82Tint(glm::clamp(first, Vec3(0.0f), Vec3(1.0f)), glm::clamp(second, Vec3(0.0f), Vec3(1.0f)));
    fss_ = f82_.fss();
  }
  const float r = std::isfinite(roughness) ? clamp01(roughness) : 0.0f;
  const float alpha = r * r;
  ggx::Shape shape(alpha);
  float table_roughness = r;
  if (const float a = std::isfinite(anisotropy) ? clamp01(anisotropy) : 0.0f; a > 0.0f) {
    const float aspect = std::sqrt(1.0f - 0.9f * a);
    const float alpha_x = std::min(alpha / aspect, 1.0f), alpha_y = alpha * aspect;
    shape = ggx::Shape(alpha_x, alpha_y, tangent, std::isfinite(rotation) ? kTwoPi * rotation : 0.0f);
    if (shape.anisotropic()) table_roughness = std::sqrt(std::sqrt(alpha_x * alpha_y));
    else shape = ggx::Shape(alpha);  // no tangent: Cycles' isotropic lobe
  }
  lobe_ = MicrofacetLobe(shape, beckmann ? MicrofacetDistribution::Beckmann : MicrofacetDistribution::GGX);
  if (multiscatter && !beckmann) multiscatter_roughness_ = table_roughness;
  if (!film.over_conductors()) return;  // no film, or a Blender whose Metallic BSDF has none (4.x)
  film_ = film;
  if (conductor) {
    film_n_ = n_;
    film_k_ = k_;
  } else {
    film_f82_ = f82_.eval(1.0f / 7.0f);
    conductor_from_f82(f82_.f0, film_f82_, film_n_, film_k_);
  }
}

Vec3 MetallicBsdf::fresnel(float cos_i) const {
  if (film_.active()) return film_.over_conductor(clamp01(cos_i), film_n_, film_k_, film_f82_);
  return conductor_ ? conductor_fresnel(cos_i, n_, k_) : f82_.eval(cos_i);
}

bool MetallicBsdf::has_delta() const { return lobe_.shape().is_delta(ggx_tables::kDeltaAlpha); }

LobeEval MetallicBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f || has_delta()) return {};
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return {};
  const float g = 1.0f / (1.0f + lobe_.lambda(wo) + lobe_.lambda(wi));
  LobeEval f;
  f.glossy = fresnel(glm::dot(wo, h)) * (lobe_.D(h) * g / (4.0f * wo.z));
  if (multiscatter_roughness_ >= 0.0f) {
    const float e = std::max(ggx_tables::albedo(multiscatter_roughness_, wo.z), 1e-3f);
    f.glossy *= multiscatter::scale(fss_, e, ggx_tables::average_albedo(multiscatter_roughness_));
  }
  return f;
}

float MetallicBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  return has_delta() ? 0.0f : lobe_.reflection_pdf(wo, wi);
}

BsdfSample MetallicBsdf::sample(const Vec3& wo, float /*u_lobe*/, const Vec2& u) const {
  BsdfSample s;
  if (wo.z <= 0.0f) return s;
  if (has_delta()) {
    s.wi = Vec3(-wo.x, -wo.y, wo.z);
    s.weight = fresnel(wo.z);
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
