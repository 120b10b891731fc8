#include "torrance/bsdfs/principled_v2.h"

#include "torrance/bsdfs/microfacet.h"

namespace torrance {

using multiscatter::mean_dielectric_fresnel;

PrincipledV2Bsdf::PrincipledV2Bsdf(const Material& m) {
  const Vec3 base = glm::max(m.base_color, Vec3(0.0f));
  const Vec3 tint = glm::max(m.specular_tint_color, Vec3(0.0f));
  metallic_ = clamp01(m.metallic);
  dielectric_weight_ = (1.0f - metallic_) * (1.0f - clamp01(m.transmission));  // the glass takes the rest
  roughness_ = clamp01(m.roughness);
  alpha_ = roughness_ * roughness_;
  shape_ = ggx::Shape(alpha_);
  table_roughness_ = roughness_;
  if (const float a = std::isfinite(m.anisotropy) ? clamp01(m.anisotropy) : 0.0f; a > 0.0f) {
    const float aspect = std::sqrt(1.0f - 0.9f * a);
    const float alpha_x = std::min(alpha_ / aspect, 1.0f), alpha_y = alpha_ * aspect;
    shape_ = ggx::Shape(alpha_x, alpha_y, m.tangent, kTwoPi * m.anisotropic_rotation);
    if (shape_.anisotropic()) table_roughness_ = std::sqrt(std::sqrt(alpha_x * alpha_y));
    else shape_ = ggx::Shape(alpha_);
  }
  multiscatter_ = m.multiscatter_ggx;

  // Metal: F82-tint with f0 = base colour (clamped to 1), tint clamped to 1.
  metal_ = F82Tint(base, tint);
  metal_fss_ = metal_.fss();
  film_ = m.thin_film();
  if (film_.over_conductors()) {
    metal_film_ = true;
    metal_f82_ = metal_.eval(1.0f / 7.0f);
    conductor_from_f82(metal_.f0, metal_f82_, metal_n_, metal_k_);
  }

  // Subsurface Weight: the walk takes that share of the diffuse layer in the channels it walks
  // (radius above 0: shade_material zeroes the others, subsurface_lobe.h), the diffuse the rest.
  diffuse_color_ = base;
  diffuse_lobe_ = EnergyPreservingOrenNayar(base, m.diffuse_roughness);
  if (const float ssw = clamp01(m.subsurface); ssw > 0.0f && m.thin_wall) {
    // Thin Wall: a Lambertian reflection and translucency share the subsurface part (Cycles 5.x).
    const float g = std::isfinite(m.subsurface_anisotropy) ? m.subsurface_anisotropy : 0.0f;
    const Vec3 clamped = glm::min(base, Vec3(1.0f)) * ssw;
    diffuse_color_ = base * (1.0f - ssw) + clamped * clamp01(0.5f * (1.0f - g));
    translucent_color_ = clamped * clamp01(0.5f * (1.0f + g));
  } else if (ssw > 0.0f) {
    const Vec3 walked(m.subsurface_radius.x > 0.0f, m.subsurface_radius.y > 0.0f, m.subsurface_radius.z > 0.0f);
    const Vec3 clamped = glm::min(base, Vec3(1.0f));
    subsurface_color_ = clamped * ssw * walked;
    diffuse_color_ = base * (1.0f - ssw) + clamped * ssw * (Vec3(1.0f) - walked);
  }

  // Dielectric: F0 from the IOR rescaled by the Specular IOR Level (f0 = 0.08 specular).
  eta_ = dielectric_eta(m);
  has_dielectric_ = eta_ != 1.0f || film_.active();
  dielectric_f0_ = glm::clamp(ggx_tables::f0_from_ior(eta_) * tint, Vec3(0.0f), Vec3(1.0f));
  const float f0_eta = ggx_tables::f0_from_ior(eta_);
  const float s_ss = f0_eta < 1.0f ? clamp01((mean_dielectric_fresnel(eta_) - f0_eta) / (1.0f - f0_eta)) : 1.0f;
  dielectric_fss_ = glm::mix(dielectric_f0_, Vec3(1.0f), s_ss);
  if (m.coat_weight > 0.0f) coat_ = CoatV2(m);
  if (m.sheen_weight > 0.0f) sheen_ = SheenV2(m.sheen_weight, m.sheen_roughness, m.sheen_tint_color);
}

float PrincipledV2Bsdf::dielectric_eta(const Material& m) {
  const float ior = std::max(m.ior, 1e-5f);
  const float f0 = 0.08f * std::max(m.specular, 0.0f);
  const float f0_ior = ggx_tables::f0_from_ior(ior);
  if (!(std::abs(f0 - f0_ior) > 1e-6f * f0_ior)) return ior;
  const float eta = ggx_tables::ior_from_f0(f0);
  return ior < 1.0f ? 1.0f / eta : eta;
}

Vec3 PrincipledV2Bsdf::metal_fresnel(float cos_ih) const {
  if (metal_film_) return film_.over_conductor(clamp01(cos_ih), metal_n_, metal_k_, metal_f82_);
  return metal_.eval(cos_ih);
}

Vec3 PrincipledV2Bsdf::dielectric_fresnel(float cos_ih) const {
  if (!has_dielectric_) return Vec3(0.0f);
  if (film_.active()) return tinted_film_fresnel(film_.over_dielectric(clamp01(cos_ih), eta_), dielectric_f0_, eta_);
  return glm::mix(dielectric_f0_, Vec3(1.0f), ggx_tables::dielectric_fresnel_factor(cos_ih, eta_));
}

Vec3 PrincipledV2Bsdf::dielectric_albedo(float cos_o) const {
  // With a film, Cycles' estimate is the Fresnel at the macro normal (it has no tables for it).
  if (film_.active()) return dielectric_fresnel(cos_o);
  return glm::mix(dielectric_f0_, Vec3(1.0f), ggx_tables::dielectric_fresnel_mix(table_roughness_, cos_o, eta_));
}

PrincipledV2Bsdf::ViewTerms PrincipledV2Bsdf::view_terms(float cos_o, float cos_coat, float cos_sheen) const {
  ViewTerms v;
  Vec3 metal_k(1.0f), dielectric_k(1.0f), darkening(1.0f);
  if (multiscatter_) {
    const float e = std::max(ggx_tables::albedo(table_roughness_, cos_o), 1e-3f);
    const float e_avg = ggx_tables::average_albedo(table_roughness_);
    metal_k = multiscatter::scale(metal_fss_, e, e_avg);
    dielectric_k = multiscatter::scale(dielectric_fss_, e, e_avg);
    darkening = e * dielectric_k;
  }
  v.metal_scale = metallic_ * metal_k;
  float diffuse_weight = 1.0f;
  if (has_dielectric_) {
    v.dielectric_scale = dielectric_weight_ * dielectric_k;
    v.dielectric_albedo = darkening * dielectric_albedo(cos_o);
    diffuse_weight = clamp01(1.0f - max_component(v.dielectric_albedo));
  }
  v.diffuse = diffuse_color_ * (dielectric_weight_ * diffuse_weight);
  if (has_subsurface()) v.subsurface = subsurface_color_ * (dielectric_weight_ * diffuse_weight);
  v.translucent = translucent_color_ * (dielectric_weight_ * diffuse_weight);
  if (coat_.active()) {
    v.coat = coat_.terms(cos_coat);
    v.metal_scale *= v.coat.base_weight;
    v.dielectric_scale *= v.coat.base_weight;
    v.diffuse *= v.coat.base_weight;
    v.subsurface *= v.coat.base_weight;
    v.translucent *= v.coat.base_weight;
  }
  if (sheen_.active()) {
    // The sheen is the top layer: everything under it (the coat too) keeps 1 - max_rgb(A).
    v.sheen = sheen_.terms(cos_sheen);
    const float keep = SheenV2::keep(v.sheen);
    v.metal_scale *= keep;
    v.dielectric_scale *= keep;
    v.diffuse *= keep;
    v.subsurface *= keep;
    v.translucent *= keep;
    v.coat.scale *= keep;
    v.coat.albedo *= keep;
  }
  return v;
}

PrincipledV2Bsdf::ClosureAlbedos PrincipledV2Bsdf::closure_albedos(float cos_o) const {
  const ViewTerms v = view_terms(cos_o);
  ClosureAlbedos a;
  // The multiscatter darkening E k: the scales above carry k (the lobe's factor).
  const float e = multiscatter_ ? std::max(ggx_tables::albedo(table_roughness_, cos_o), 1e-3f) : 1.0f;
  a.diffuse = v.diffuse + v.subsurface + v.translucent;  // a BSSRDF's albedo is its weight (Cycles)
  if (has_dielectric_) a.dielectric = v.dielectric_scale * e * dielectric_albedo(cos_o);
  a.metal = v.metal_scale * e *
            (metal_film_ ? metal_fresnel(cos_o)
                         : glm::mix(metal_.f0, Vec3(1.0f), ggx_tables::schlick_fresnel_mix(table_roughness_, cos_o)));
  if (coat_.active()) a.coat = Vec3(v.coat.albedo);
  if (sheen_.active()) {
    a.sheen = v.sheen.weight;
    a.layers = v.coat.base_weight * SheenV2::keep(v.sheen);
  } else {
    a.layers = v.coat.base_weight;
  }
  return a;
}

Vec3 PrincipledV2Bsdf::emission_weight(const Material& m, float cos_coat, float cos_sheen) {
  const CoatV2 coat = m.coat_weight > 0.0f ? CoatV2(m) : CoatV2();
  const SheenV2 sheen = m.sheen_weight > 0.0f ? SheenV2(m.sheen_weight, m.sheen_roughness, m.sheen_tint_color) : SheenV2();
  return emission_weight(coat, sheen, cos_coat, cos_sheen);
}

Vec3 PrincipledV2Bsdf::emission_weight(const CoatV2& coat, const SheenV2& sheen, float cos_coat, float cos_sheen) {
  Vec3 w(1.0f);
  if (coat.active()) w *= coat.terms(clamp01(cos_coat)).base_weight;
  if (sheen.active()) w *= SheenV2::keep(sheen.terms(clamp01(cos_sheen)));
  return w;
}

Vec3 PrincipledV2Bsdf::mirror_reflectance(const Vec3& wo) const {
  const ViewTerms v = view_terms(wo.z);
  return v.metal_scale * metal_fresnel(wo.z) + v.dielectric_scale * dielectric_fresnel(wo.z);
}

Vec3 PrincipledV2Bsdf::specular_estimate(const ViewTerms& v, float cos_o) const {
  const Vec3 spec = metallic_ * metal_fresnel(cos_o) + (1.0f - metallic_) * v.dielectric_albedo;
  return spec * v.coat.base_weight * (sheen_.active() ? SheenV2::keep(v.sheen) : 1.0f);
}

float PrincipledV2Bsdf::specular_probability(const ViewTerms& v, float cos_o) const {
  return lobe_mixture::specular_probability(luminance(specular_estimate(v, cos_o)), luminance(v.diffuse));
}

PrincipledV2Bsdf::View PrincipledV2Bsdf::geometry(const Vec3& wo, const CoatNormal& coat) const {
  View v;
  lobe_mixture::prepare(v, wo, shape_);
  v.coat_normal = coat;
  if (sheen_.active()) v.sheen_normal = coat.sheen_normal(coat_.weight());
  v.terms = view_terms(wo.z, v.coat_normal.cosine(wo), v.sheen_normal.cosine(wo));
  v.lambda_o = shape_.lambda(wo);
  if (sheen_.active()) v.sheen = SheenBsdf::oriented(v.terms.sheen, v.sheen_normal.to_coat(wo));
  return v;
}

PrincipledV2Bsdf::View PrincipledV2Bsdf::at(const Vec3& wo, const CoatNormal& coat) const {
  View v = geometry(wo, coat);
  v.p_spec = specular_probability(v.terms, wo.z);
  const ViewTerms& t = v.terms;
  if (coat_.reflects() || sheen_.active()) {
    const float under_coat = luminance(specular_estimate(t, wo.z) + t.diffuse);
    if (coat_.reflects()) v.p_coat = lobe_mixture::coat_probability(t.coat.albedo, under_coat);
    if (v.sheen.reflects())
      v.p_sheen = lobe_mixture::coat_probability(luminance(v.sheen.weight), under_coat + t.coat.albedo);
  }
  return v;
}

LobeEval PrincipledV2Bsdf::eval_lobes(const View& view, const Vec3& wi) const {
  const Vec3& wo = view.wo;
  if (wo.z <= 0.0f) return {};
  const ViewTerms& v = view.terms;
  LobeEval f_cos;
  const float cos_diffuse = view.diffuse_normal.cosine(wi);
  if (cos_diffuse > 0.0f && diffuse_lobe_.lambertian()) {
    f_cos.diffuse = v.diffuse * (kInvPi * cos_diffuse);
  } else if (cos_diffuse > 0.0f) {
    const float cos_o = view.diffuse_normal.cosine(wo);
    f_cos.diffuse = v.diffuse * diffuse_lobe_.reflectance_cos(cos_diffuse, cos_o, glm::dot(wi, wo));
  }
  // The coat about its own normal (whatever side of the shading normal wi lies on).
  if (coat_.reflects())
    f_cos.glossy = Vec3(coat_.eval(v.coat, view.coat_normal.to_coat(wo), view.coat_normal.to_coat(wi)));
  // The sheen about its own normal likewise.
  if (view.sheen.reflects()) f_cos.diffuse += view.sheen.weight * sheen_pdf(view, wi);
  if (wi.z <= 0.0f) return f_cos;
  if (has_delta()) return f_cos;
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return f_cos;
  const float cos_d = clamp01(glm::dot(wi, h));
  const Vec3 fresnel = v.metal_scale * metal_fresnel(cos_d) + v.dielectric_scale * dielectric_fresnel(cos_d);
  const float g2 = 1.0f / (1.0f + view.lambda_o + shape_.lambda(wi));  // height-correlated Smith
  f_cos.glossy += fresnel * (shape_.D(h) * g2 / view.four_cos_o);
  return f_cos;
}

}  // namespace torrance
