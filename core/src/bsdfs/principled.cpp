#include "torrance/bsdfs/principled.h"

#include "torrance/subsurface/subsurface_lobe.h"

namespace torrance {

float fresnel_dielectric(float cos_i, float eta) {
  const float c = std::abs(cos_i);
  const float g2 = eta * eta - 1.0f + c * c;
  if (g2 <= 0.0f) return 1.0f;  // total internal reflection
  const float g = std::sqrt(g2);
  const float a = (g - c) / (g + c);
  const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  return 0.5f * a * a * (1.0f + b * b);
}

Vec3 fresnel_interpolated(const Vec3& cspec0, float cos_ih, float eta, float f0) {
  const float fh = f0 < 1.0f ? clamp01((fresnel_dielectric(cos_ih, eta) - f0) / (1.0f - f0)) : 1.0f;
  return cspec0 * (1.0f - fh) + Vec3(fh);
}

PrincipledBsdf::PrincipledBsdf(const Material& m) {
  const Vec3 base = glm::clamp(m.base_color, Vec3(0.0f), Vec3(1.0f));
  const float metallic = clamp01(m.metallic);
  roughness_ = clamp01(m.roughness);
  alpha_ = roughness_ * roughness_;
  shape_ = ggx::Shape(alpha_);
  if (m.anisotropy != 0.0f && std::isfinite(m.anisotropy)) {
    // Cycles 3.4: aspect = sqrt(1 - 0.9 a) (Blender's socket keeps a in [0, 1]; Material's [-1, 1]
    // keeps it positive), each alpha clamped to 1 by the closure's set-up.
    const float aspect = std::sqrt(1.0f - 0.9f * std::clamp(m.anisotropy, -1.0f, 1.0f));
    shape_ = ggx::Shape(std::min(alpha_ / aspect, 1.0f), std::min(alpha_ * aspect, 1.0f), m.tangent,
                        kTwoPi * m.anisotropic_rotation);
    if (!shape_.anisotropic()) shape_ = ggx::Shape(alpha_);
  }
  // Transmission (Cycles 3.4): the diffuse lobe keeps (1 - metallic)(1 - transmission), the
  // specular lobe 1 - transmission (1 - metallic); the rest is glass (MaterialBsdf, glass.h).
  const float transmission = clamp01(m.transmission);
  const float diffuse_weight = (1.0f - metallic) * (1.0f - transmission);
  // Subsurface (Cycles 3.4): the diffuse lobe's colour is the subsurface-mixed one, and the random
  // walk takes its Lambertian part (subsurface_lobe.h), but in channels whose radius is too small.
  subsurface_ = m.subsurface > 0.0f;
  if (subsurface_) lambert_channels_ = principled_lambert_channels(m);
  diffuse_color_ = diffuse_weight * (subsurface_ ? glm::clamp(principled_subsurface_albedo(m), Vec3(0.0f), Vec3(1.0f)) : base);
  diffuse_luminance_ = luminance(diffuse_color_);
  specular_weight_ = 1.0f - transmission * (1.0f - metallic);
  f0_ = std::min(0.08f * std::max(m.specular, 0.0f), 0.99f);
  const float sqrt_f0 = std::sqrt(f0_);
  eta_ = 2.0f / (1.0f - sqrt_f0) - 1.0f;
  const float lum = 0.3f * base.r + 0.6f * base.g + 0.1f * base.b;  // Cycles' tint luminance weights
  const Vec3 tint = lum > 0.0f ? base / lum : Vec3(1.0f);
  const Vec3 dielectric = f0_ * glm::mix(Vec3(1.0f), tint, clamp01(m.specular_tint)) * (1.0f - metallic);
  cspec0_ = glm::clamp(dielectric + base * metallic, Vec3(0.0f), Vec3(1.0f));
  // Cycles 3.4's Multiscatter GGX above roughness 0.075 (single-scattering GGX below); with glass
  // the material keeps single scattering (MaterialBsdf's glass mix counts eval / pdf).
  if (shape_.is_delta(ggx::kDeltaAlpha)) specular_ = Specular::Mirror;
  else if (m.multiscatter_walk && roughness_ > 0.075f && !m.transmits()) specular_ = Specular::Walk;
  if (m.coat_weight > 0.0f) coat_ = ClearcoatV1(m.coat_weight, m.coat_roughness);
  if (m.sheen_weight > 0.0f) sheen_ = SheenV1(m.sheen_weight, m.sheen_tint, base, diffuse_weight);
}

microsurface::Walk PrincipledBsdf::walk() const {
  microsurface::Reflectance r;
  r.fresnel = true;
  r.cspec0 = cspec0_;
  r.eta = eta_;
  r.f0 = f0_;
  return microsurface::Walk(shape_, r);
}

Vec3 PrincipledBsdf::fresnel(float cos_ih) const {
  if (f0_ <= 0.0f) return specular_weight_ * cspec0_;
  return specular_weight_ * fresnel_interpolated(cspec0_, cos_ih, eta_, f0_);
}

float PrincipledBsdf::specular_probability(const Vec3& wo) const {
  // The sheen is sampled with the diffuse lobe (by the cosine): its estimate joins the diffuse's.
  const float diffuse = sheen_.active() ? diffuse_luminance_ + sheen_.estimate(wo.z) : diffuse_luminance_;
  // Without a diffuse lobe the answer is 1 whatever F is: no Fresnel then (metals, mirrors).
  if (!(diffuse > 0.0f)) return 1.0f;
  return lobe_mixture::specular_probability(luminance(fresnel(wo.z)), diffuse);
}

PrincipledBsdf::View PrincipledBsdf::geometry(const Vec3& wo, const CoatNormal& coat) const {
  View v;
  lobe_mixture::prepare(v, wo, shape_);
  v.coat_normal = coat;
  v.burley_o = schlick_weight(wo.z);
  return v;
}

PrincipledBsdf::View PrincipledBsdf::at(const Vec3& wo, const CoatNormal& coat_normal) const {
  View v = geometry(wo, coat_normal);
  v.p_spec = specular_probability(wo);
  if (coat_.active()) {
    // Cycles' closure odds, unclamped: the clearcoat's w F(wo.z), the mean diffuse colour and the
    // mean specular Fresnel. The clearcoat's estimator is biased (principled_coat.h) by an amount
    // that depends on them: with Cycles' odds it is Cycles' bias.
    const float coat = coat_.estimate(v.coat_normal.cosine(wo));
    float diffuse = (diffuse_color_.r + diffuse_color_.g + diffuse_color_.b) / 3.0f;
    if (sheen_.active()) diffuse += sheen_.estimate(wo.z);
    const float spec = glm::dot(fresnel(wo.z), Vec3(1.0f)) / 3.0f;
    const float all = coat + diffuse + spec;
    v.p_coat = all > 0.0f ? coat / all : 0.0f;
    v.p_spec = spec + diffuse > 0.0f ? spec / (spec + diffuse) : 1.0f;
  }
  return v;
}

template <bool kWithWalk>
LobeEval PrincipledBsdf::eval_parts(const View& v, const Vec3& wi) const {
  const Vec3& wo = v.wo;
  if (wo.z <= 0.0f) return {};
  LobeEval f_cos;
  // The clearcoat about its own normal (whatever side of the shading normal wi lies on).
  if (coat_.active()) f_cos.glossy = Vec3(coat_.eval(v.coat_normal.to_coat(wo), v.coat_normal.to_coat(wi)));
  Vec3 h;
  if (wi.z <= 0.0f || !ggx::reflection_half(wo, wi, h)) return f_cos;
  const float cos_d = clamp01(glm::dot(wi, h));

  // Burley diffuse (Cycles 3.4's principled diffuse, roughness unsquared).
  const float fl = schlick_weight(wi.z), fv = v.burley_o;
  const float rr = 2.0f * roughness_ * cos_d * cos_d;
  if (subsurface_) {
    const float lambert = (1.0f - 0.5f * fl) * (1.0f - 0.5f * fv), retro = rr * (fl + fv + fl * fv * (rr - 1.0f));
    f_cos.diffuse = diffuse_color_ * (lambert_channels_ * lambert + Vec3(retro)) * (kInvPi * wi.z);
  } else {
    const float burley = (1.0f - 0.5f * fl) * (1.0f - 0.5f * fv) + rr * (fl + fv + fl * fv * (rr - 1.0f));
    f_cos.diffuse = diffuse_color_ * (kInvPi * burley * wi.z);
  }
  if (sheen_.active()) f_cos.diffuse += sheen_.eval(cos_d, wi.z);
  if (specular_ == Specular::Ggx) {
    const float g = v.g1_o * shape_.G1(wi);
    f_cos.glossy = fresnel(cos_d) * (shape_.D(h) * g / v.four_cos_o) + f_cos.glossy;
  } else if (kWithWalk && specular_ == Specular::Walk) {
    f_cos.glossy += specular_weight_ * walk().eval(wo, wi);
  }
  return f_cos;
}
template LobeEval PrincipledBsdf::eval_parts<true>(const View& v, const Vec3& wi) const;
template LobeEval PrincipledBsdf::eval_parts<false>(const View& v, const Vec3& wi) const;

}  // namespace torrance
