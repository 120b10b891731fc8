#include "torrance/bsdfs/principled_glass_v2.h"

#include "torrance/bsdfs/ggx_glass_tables.h"
#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/glossy_bsdf.h"  // the node's anisotropy
#include "torrance/bsdfs/microfacet.h"
#include "torrance/bsdfs/outward.h"
#include "torrance/bsdfs/principled_coat.h"  // multiscatter
#include "torrance/bsdfs/refraction_pair.h"

namespace torrance {

namespace {

float mean(const Vec3& v) { return (v.x + v.y + v.z) / 3.0f; }

float valid_ior(float ior) { return std::isfinite(ior) ? std::min(std::max(ior, 1e-5f), 1e3f) : 1.5f; }

}  // namespace

PrincipledGlassV2::PrincipledGlassV2(float roughness, float ior, const Vec3& specular_tint, const Vec3& base_color,
                                     bool multiscatter, const ThinFilm& film)
    : PrincipledGlassV2(roughness, ior, specular_tint, base_color, multiscatter, film, ior) {}

PrincipledGlassV2::PrincipledGlassV2(float roughness, float ior, const Vec3& specular_tint, const Vec3& base_color,
                                     bool multiscatter, const ThinFilm& film, float refracting_ior)
    : film_(film), film_inside_(film) {
  roughness_ = clamp01(std::isfinite(roughness) ? roughness : 0.0f);
  alpha_ = roughness_ * roughness_;
  ior_ = valid_ior(refracting_ior);
  f0_ = glm::clamp(ggx_tables::f0_from_ior(valid_ior(ior)) * glm::max(specular_tint, Vec3(0.0f)), Vec3(0.0f),
                   Vec3(1.0f));
  tint_t_ = glm::sqrt(glm::clamp(base_color, Vec3(0.0f), Vec3(1.0f)));
  smooth_ = alpha_ < ggx_tables::kDeltaAlpha;
  straight_ = std::abs(ior_ - 1.0f) < 1e-4f;
  invisible_ = straight_ && !film.active();  // a film still reflects (a soap bubble)
  multiscatter_ = multiscatter;
  lobe_ = MicrofacetLobe(ggx::Shape(alpha_), MicrofacetDistribution::GGX);
  film_inside_.ior = film.ior / ior_;
}

PrincipledGlassV2 PrincipledGlassV2::glass_node(float roughness, float ior, const Vec3& color, bool multiscatter,
                                                const ThinFilm& film, bool beckmann) {
  PrincipledGlassV2 glass(roughness, ior, Vec3(1.0f), Vec3(1.0f), multiscatter && !beckmann, film);
  const Vec3 tint = is_finite(color) ? glm::max(color, Vec3(0.0f)) : Vec3(0.0f);
  glass.tint_r_ = glass.tint_t_ = tint;
  const auto distribution = beckmann ? MicrofacetDistribution::Beckmann : MicrofacetDistribution::GGX;
  glass.lobe_ = MicrofacetLobe(ggx::Shape(glass.alpha_), distribution);
  return glass;
}

PrincipledGlassV2 PrincipledGlassV2::refraction_node(float roughness, float ior, const Vec3& color, bool beckmann) {
  PrincipledGlassV2 glass = glass_node(roughness, ior, color, false, ThinFilm{}, beckmann);
  glass.tint_r_ = Vec3(0.0f);
  glass.reflective_ = false;
  return glass;
}

void PrincipledGlassV2::stretch(const ggx::Shape& shape) {
  if (!shape.anisotropic()) return;
  lobe_ = MicrofacetLobe(shape, lobe_.distribution());
  roughness_ = std::sqrt(std::sqrt(shape.alpha_x() * shape.alpha_y()));
  smooth_ = shape.is_delta(ggx_tables::kDeltaAlpha);
}

void PrincipledGlassV2::stretch_as_node(float anisotropy, const Vec3& tangent, float rotation) {
  stretch(GlossyBsdf::lobe_shape(roughness_, anisotropy, tangent, rotation));
}

PrincipledGlassV2::Split PrincipledGlassV2::split(float c, float etap) const {
  Split out;
  if (!reflective_) {  // the Refraction node: no Fresnel, nothing at total internal reflection
    out.p_reflect = 0.0f;
    if (1.0f - (1.0f - c * c) / (etap * etap) > 0.0f) out.transmit = tint_t_;
    return out;
  }
  if (film_.active()) {
    const ThinFilm& film = etap == ior_ ? film_ : film_inside_;
    out.reflect = tinted_film_fresnel(film.over_dielectric(clamp01(c), etap), f0_, etap);
  } else {
    out.reflect = glm::mix(f0_, Vec3(1.0f), ggx_tables::dielectric_fresnel_factor(c, etap));
  }
  out.transmit = (Vec3(1.0f) - out.reflect) * tint_t_;
  out.reflect *= tint_r_;
  const float total = mean(out.reflect + out.transmit);
  out.p_reflect = total > 0.0f ? mean(out.reflect) / total : 1.0f;
  return out;
}

Vec3 PrincipledGlassV2::energy_scale(float cos_o, float etap) const {
  if (!multiscatter_ || smooth_) return Vec3(1.0f);
  const float e = std::max(ggx_glass_tables::albedo(roughness_, cos_o, etap), 1e-3f);
  const float e_avg = ggx_glass_tables::average_albedo(roughness_, etap);
  Vec3 fss = tint_t_;
  if (fss == Vec3(0.0f)) {  // no transmission tint: the reflection's mean Fresnel (Cycles)
    const float f0_real = ggx_tables::f0_from_ior(etap);
    const float s = clamp01((multiscatter::mean_dielectric_fresnel(etap) - f0_real) / (1.0f - f0_real));
    fss = tint_r_ * glm::mix(f0_, Vec3(1.0f), s);
  }
  return multiscatter::scale(fss, e, e_avg);
}

PrincipledGlassV2::Lobe PrincipledGlassV2::evaluate(const Vec3& wo, const Vec3& wi, float etap) const {
  Lobe out;
  if (smooth_ || invisible_ || !(wo.z > 0.0f) || wi.z == 0.0f) return out;
  const float g2 = 1.0f / (1.0f + lobe_.lambda(wo) + lobe_.lambda(Vec3(wi.x, wi.y, std::abs(wi.z))));
  const float g1_o = lobe_.visible_g1(wo);
  if (wi.z > 0.0f) {
    Vec3 h;
    if (!reflective_ || !ggx::reflection_half(wo, wi, h)) return out;
    const Split sp = split(glm::dot(wo, h), etap);
    const float common = lobe_.D(h) / (4.0f * wo.z);
    out.f_cos = sp.reflect * (common * g2);
    out.pdf = sp.p_reflect * common * g1_o;
  } else {
    RefractionPair p;
    if (straight_) return out;  // a delta straight through, sampled only
    if (!refraction_pair(wo, wi, etap, p)) return out;  // also pairs no microfacet connects, as Cycles
    const Split sp = split(p.o_h, etap);
    if (sp.transmit == Vec3(0.0f)) return out;  // Cycles: nothing reflected or transmitted, no pdf
    const float common = lobe_.D(p.h) / wo.z * etap * etap * p.o_h * p.i_h / p.len2;
    out.f_cos = sp.transmit * (common * g2);
    out.pdf = (1.0f - sp.p_reflect) * common * g1_o;
  }
  out.f_cos *= energy_scale(wo.z, etap);
  if (!is_finite(out.f_cos) || !std::isfinite(out.pdf)) return Lobe{};
  return out;
}

Vec3 PrincipledGlassV2::eval(const Vec3& wo, const Vec3& wi) const {
  const bool inside = wo.z < 0.0f;
  return evaluate(outward(wo, inside), outward(wi, inside), inside ? 1.0f / ior_ : ior_).f_cos;
}

float PrincipledGlassV2::pdf(const Vec3& wo, const Vec3& wi) const {
  const bool inside = wo.z < 0.0f;
  return evaluate(outward(wo, inside), outward(wi, inside), inside ? 1.0f / ior_ : ior_).pdf;
}

bool PrincipledGlassV2::connects(const Vec3& wo, const Vec3& wi) const {
  const bool inside = wo.z < 0.0f;
  const Vec3 o = outward(wo, inside), i = outward(wi, inside);
  return !(o.z > 0.0f && i.z < 0.0f) || refraction_connects(o, i, inside ? 1.0f / ior_ : ior_);
}

BsdfSample PrincipledGlassV2::sample(const Vec3& wo_outward, float u_lobe, const Vec2& u) const {
  BsdfSample s;
  if (wo_outward.z == 0.0f || !is_finite(wo_outward)) return s;
  const bool inside = wo_outward.z < 0.0f;
  const Vec3 wo = outward(wo_outward, inside);
  const float etap = inside ? 1.0f / ior_ : ior_;
  if (invisible_) {
    s.wi = -wo_outward;
    s.weight = tint_t_;
    s.is_delta = true;
    return s;
  }
  const Vec3 h = smooth_ ? Vec3(0.0f, 0.0f, 1.0f) : lobe_.sample_visible_normal(wo, u);
  const float c = glm::dot(wo, h);
  if (!(c > 0.0f)) return s;
  const Split sp = split(c, etap);
  if (sp.reflect == Vec3(0.0f) && sp.transmit == Vec3(0.0f)) return s;
  const bool reflect = u_lobe < sp.p_reflect;
  Vec3 wi;
  if (reflect) {
    wi = ggx::reflect(wo, h);
    if (!(wi.z > 0.0f)) return BsdfSample{};
  } else if (straight_) {  // under a film: what the microfacet does not reflect passes straight (Cycles)
    s.wi = -wo_outward;
    s.weight = sp.transmit / (1.0f - sp.p_reflect);
    s.is_delta = true;
    return s;
  } else if (!ggx::refract(wo, h, etap, wi) || !(wi.z < 0.0f)) {
    return BsdfSample{};
  }
  s.wi = outward(wi, inside);
  if (smooth_) {
    s.weight = reflect ? sp.reflect / sp.p_reflect : sp.transmit / (1.0f - sp.p_reflect);
    s.is_delta = true;
    return s;
  }
  const Lobe l = evaluate(wo, wi, etap);
  if (!(l.pdf > 0.0f)) return BsdfSample{};
  s.pdf = l.pdf;
  s.weight = l.f_cos / l.pdf;
  return s;
}

}  // namespace torrance
