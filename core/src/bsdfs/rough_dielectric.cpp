#include "torrance/bsdfs/rough_dielectric.h"

#include "torrance/bsdfs/principled.h"  // fresnel_dielectric

namespace torrance {

namespace {

// GGX D of a microfacet normal m given on either side: the distribution is symmetric about the
// tangent plane, so it is evaluated for m turned to z > 0.
float D_either_side(const Vec3& m, float alpha) { return ggx::D(m.z < 0.0f ? -m : m, alpha); }

}  // namespace

RoughDielectricBsdf::RoughDielectricBsdf(float roughness, float ior, const Vec3& color)
    : color_(glm::max(color, Vec3(0.0f))) {
  const float r = clamp01(std::isfinite(roughness) ? roughness : 0.0f);
  alpha_ = r * r;
  eta_ = std::isfinite(ior) ? std::min(std::max(ior, 1e-3f), 1e3f) : 1.0f;
  smooth_ = alpha_ < ggx::kDeltaAlpha;
  invisible_ = std::abs(eta_ - 1.0f) < 1e-4f;
}

float RoughDielectricBsdf::mirror_reflectance(const Vec3& wo) const {
  if (invisible_ || wo.z == 0.0f) return 0.0f;
  return fresnel_dielectric(wo.z, wo.z > 0.0f ? eta_ : 1.0f / eta_);
}

RoughDielectricBsdf::Lobe RoughDielectricBsdf::evaluate(const Vec3& wo, const Vec3& wi) const {
  Lobe out;
  if (smooth_ || invisible_ || wo.z == 0.0f || wi.z == 0.0f) return out;
  const float cos_o = std::abs(wo.z), cos_i = std::abs(wi.z);
  const float side = wo.z > 0.0f ? 1.0f : -1.0f;
  const float etap = wo.z > 0.0f ? eta_ : 1.0f / eta_;  // eta(wi side) / eta(wo side) when refracting
  const float g1_o = ggx::smith_G1(cos_o, alpha_);
  if (wo.z * wi.z > 0.0f) {
    // Reflection: wo + wi points into wo's side, so h faces wo and wi.
    Vec3 h;
    if (!ggx::reflection_half(wo, wi, h)) return out;
    const float F = fresnel_dielectric(glm::dot(wo, h), etap);
    const float D = D_either_side(h, alpha_);
    out.f_cos = F * D * g1_o * ggx::smith_G1(cos_i, alpha_) / (4.0f * cos_o);
    out.pdf = F * g1_o * D / (4.0f * cos_o);
    return out;
  }
  // Refraction: the generalised half vector, turned to wo's side.
  const Vec3 half = wo + etap * wi;
  const float len2 = glm::dot(half, half);  // = (wo.h + etap wi.h)^2: no cancellation of the two dots
  if (!(len2 > 0.0f)) return out;
  Vec3 h = half / std::sqrt(len2);
  if (h.z * side < 0.0f) h = -h;
  const float o_h = glm::dot(wo, h), i_h = glm::dot(wi, h);
  if (!(o_h > 0.0f) || !(i_h < 0.0f)) return out;  // the microfacet must face wo and be crossed by wi
  // 1 - F from both cosines of the refraction pair (Fresnel's r_s, r_p with 1 - r^2 factored):
  // exact in either direction, where F(cos) alone loses 1 - F to cancellation near the critical angle.
  const float c_o = o_h, c_i = -i_h;
  const float transmit = 2.0f * etap * c_o * c_i * (1.0f / sqr(c_o + etap * c_i) + 1.0f / sqr(etap * c_o + c_i));
  if (!(transmit > 0.0f)) return out;
  const float D = D_either_side(h, alpha_);
  const float jacobian = etap * etap * c_i / len2;  // dh/dwi (Walter eq. 17), eta_o = 1 relative
  const float visible_h = g1_o * D * o_h / cos_o;   // density of h from visible-normal sampling
  out.f_cos = transmit * visible_h * jacobian * ggx::smith_G1(cos_i, alpha_);
  out.pdf = transmit * visible_h * jacobian;
  if (!std::isfinite(out.f_cos) || !std::isfinite(out.pdf)) return Lobe{};
  return out;
}

Vec3 RoughDielectricBsdf::eval(const Vec3& wo, const Vec3& wi) const { return color_ * evaluate(wo, wi).f_cos; }

float RoughDielectricBsdf::pdf(const Vec3& wo, const Vec3& wi) const { return evaluate(wo, wi).pdf; }

BsdfSample RoughDielectricBsdf::sample(const Vec3& wo, float u_lobe, const Vec2& u) const {
  BsdfSample s;
  if (wo.z == 0.0f || !is_finite(wo)) return s;
  if (invisible_) {
    s.wi = -wo;
    s.weight = color_;
    s.is_delta = true;
    return s;
  }
  const float side = wo.z > 0.0f ? 1.0f : -1.0f;
  const float etap = wo.z > 0.0f ? eta_ : 1.0f / eta_;
  // The microfacet normal m on wo's side (the macro normal when smooth).
  Vec3 m(0.0f, 0.0f, side);
  if (!smooth_) m = side * ggx::sample_visible_normal(side * wo, alpha_, u);
  const float o_m = glm::dot(wo, m);
  if (!(o_m > 0.0f)) return BsdfSample{};
  const float F = fresnel_dielectric(o_m, etap);
  if (u_lobe < F) {
    s.wi = 2.0f * o_m * m - wo;
    if (!(s.wi.z * side > 0.0f)) return BsdfSample{};  // reflected below the macro surface
  } else {
    // Snell with delta = etap^2 - 1 formed without cancellation: etap cos_t = sqrt(o_m^2 + delta),
    // wi = (-wo + (o_m - etap cos_t) m) / etap, and o_m - sqrt(o_m^2 + delta) = -delta / (o_m + sqrt(..)).
    const float delta = wo.z > 0.0f ? (eta_ - 1.0f) * (eta_ + 1.0f) : (1.0f - eta_) * (1.0f + eta_) / (eta_ * eta_);
    const float g2 = o_m * o_m + delta;
    if (!(g2 > 0.0f)) return BsdfSample{};  // total internal reflection (F = 1: not reached)
    const float k = -delta / (o_m + std::sqrt(g2));
    s.wi = glm::normalize(k * m - wo);
    if (!(s.wi.z * side < 0.0f)) return BsdfSample{};  // refracted back to wo's side
  }
  if (smooth_) {
    s.weight = color_;  // F / F or (1 - F) / (1 - F)
    s.is_delta = true;
    return s;
  }
  const Lobe l = evaluate(wo, s.wi);
  if (!(l.pdf > 0.0f)) return BsdfSample{};
  s.pdf = l.pdf;
  s.weight = color_ * (l.f_cos / l.pdf);
  return s;
}

}  // namespace torrance
