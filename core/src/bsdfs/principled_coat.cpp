#include "torrance/bsdfs/principled_coat.h"

#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/microfacet.h"
#include "torrance/bsdfs/principled.h"

namespace torrance {

namespace multiscatter {

float mean_dielectric_fresnel(float eta) {
  if (eta < 1.0f) return 0.997118f + eta * (0.1014f - eta * (0.965241f + eta * 0.130607f));
  return (eta - 1.0f) / (4.08567f + 1.00071f * eta);
}

Vec3 scale(const Vec3& fss, float e, float e_avg) {
  const Vec3 fms = fss * e_avg / (Vec3(1.0f) - fss * (1.0f - e_avg));
  return Vec3(1.0f) + fms * ((1.0f - e) / e);
}

}  // namespace multiscatter

// ---- ClearcoatV1 (Cycles 3.4) ----------------------------------------------------------------

namespace {
constexpr float kClearcoatIor = 1.5f;
constexpr float kClearcoatMaskingAlpha = 0.25f;

// Both coats draw GGX's visible normals of their alpha: the direction and its density.
Vec3 visible_normal_reflection(const Vec3& wo, const Vec2& u, float alpha) {
  return ggx::reflect(wo, ggx::sample_visible_normal(wo, alpha, u));
}
float visible_normal_reflection_pdf(const Vec3& wo, const Vec3& wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return 0.0f;
  return ggx::reflected_pdf(wo, h, alpha);
}

// The GTR1 distribution of Cycles 3.4's clearcoat, a in (0, 1].
float gtr1(float cos_h, float a) {
  if (a >= 1.0f) return kInvPi;
  const float a2 = a * a;
  const float t = 1.0f + (a2 - 1.0f) * cos_h * cos_h;
  return (a2 - 1.0f) / (kPi * std::log(a2) * t);
}
}  // namespace

ClearcoatV1::ClearcoatV1(float clearcoat, float roughness) {
  const float c = std::isfinite(clearcoat) ? std::max(clearcoat, 0.0f) : 0.0f;
  weight_ = 0.25f * c;
  const float r = std::isfinite(roughness) ? roughness : 0.0f;
  alpha_ = clamp01(r * r);
}

bool ClearcoatV1::is_delta() const { return alpha_ < ggx::kDeltaAlpha; }

float ClearcoatV1::estimate(float cos_o) const { return weight_ * fresnel_dielectric(cos_o, kClearcoatIor); }

float ClearcoatV1::eval(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f || is_delta()) return 0.0f;
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return 0.0f;
  const float g = ggx::smith_G1(wo.z, kClearcoatMaskingAlpha) * ggx::smith_G1(wi.z, kClearcoatMaskingAlpha);
  const float f = fresnel_dielectric(glm::dot(wi, h), kClearcoatIor);
  return weight_ * f * gtr1(h.z, alpha_) * g / (4.0f * wo.z);
}

float ClearcoatV1::pdf(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f || is_delta()) return 0.0f;
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return 0.0f;
  return ggx::smith_G1(wo.z, kClearcoatMaskingAlpha) * gtr1(h.z, alpha_) / (4.0f * wo.z);
}

float ClearcoatV1::sampling_pdf(const Vec3& wo, const Vec3& wi) const {
  return is_delta() ? 0.0f : visible_normal_reflection_pdf(wo, wi, alpha_);
}

Vec3 ClearcoatV1::sample(const Vec3& wo, const Vec2& u) const { return visible_normal_reflection(wo, u, alpha_); }

// ---- CoatV2 (Cycles 4.x) ---------------------------------------------------------------------

CoatV2::CoatV2(float weight, float roughness, float ior, const Vec3& tint, CoatLayering layering) {
  weight_ = std::isfinite(weight) ? std::max(weight, 0.0f) : 0.0f;
  roughness_ = std::isfinite(roughness) ? clamp01(roughness) : 0.0f;
  alpha_ = roughness_ * roughness_;
  eta_ = std::isfinite(ior) ? std::max(ior, 1.0f) : 1.0f;
  fss_ = multiscatter::mean_dielectric_fresnel(eta_);
  tint_ = glm::max(tint, Vec3(0.0f));
  tinted_ = tint_ != Vec3(1.0f);
  layering_ = layering;
}

bool CoatV2::is_delta() const { return alpha_ < ggx_tables::kDeltaAlpha; }

Vec3 CoatV2::through_coat(float cos_o) const {
  // wo refracted into the coat (no total internal reflection from outside).
  const float inv_eta = 1.0f / eta_;
  const float cos_t = std::sqrt(std::max(1.0f - inv_eta * inv_eta * (1.0f - cos_o * cos_o), 0.0f));
  return glm::pow(tint_, Vec3(1.0f / std::max(cos_t, 1e-6f)));
}

CoatV2::Terms CoatV2::terms(float cos_o) const {
  Terms t;
  if (!active()) return t;
  float estimate = 0.0f;  // A
  if (eta_ > 1.0f && layering_ == CoatLayering::Cycles4_2) {
    t.scale = weight_;
    estimate = fresnel_dielectric(cos_o, eta_);
  } else if (eta_ > 1.0f) {
    const float e = std::max(ggx_tables::albedo(roughness_, cos_o), 1e-3f);
    const float k = multiscatter::scale(Vec3(fss_), e, ggx_tables::average_albedo(roughness_)).x;
    t.scale = weight_ * k;
    const float fresnel = glm::mix(ggx_tables::f0_from_ior(eta_), 1.0f,
                                   ggx_tables::dielectric_fresnel_mix(roughness_, cos_o, eta_));
    estimate = layering_ == CoatLayering::Cycles5_1 ? fresnel : e * k * fresnel;
  }
  t.albedo = weight_ * estimate;
  const Vec3 through = tinted_ ? through_coat(cos_o) : Vec3(1.0f);
  if (layering_ == CoatLayering::Cycles5_1) {
    t.base_weight = glm::clamp(Vec3(1.0f) - weight_ * (Vec3(1.0f) - through * (1.0f - estimate)), Vec3(0.0f), Vec3(1.0f));
    return t;
  }
  t.base_weight = Vec3(clamp01(1.0f - t.albedo));
  if (tinted_) t.base_weight *= glm::max(glm::mix(Vec3(1.0f), through, weight_), Vec3(0.0f));
  return t;
}

float CoatV2::eval(const Terms& t, const Vec3& wo, const Vec3& wi) const {
  if (!(t.scale > 0.0f) || wo.z <= 0.0f || wi.z <= 0.0f || is_delta()) return 0.0f;
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return 0.0f;
  const float f = fresnel_dielectric(glm::dot(wi, h), eta_);
  return t.scale * f * ggx::D(h, alpha_) * ggx::smith_G2_correlated(wo.z, wi.z, alpha_) / (4.0f * wo.z);
}

float CoatV2::pdf(const Vec3& wo, const Vec3& wi) const {
  return is_delta() ? 0.0f : visible_normal_reflection_pdf(wo, wi, alpha_);
}

Vec3 CoatV2::sample(const Vec3& wo, const Vec2& u) const { return visible_normal_reflection(wo, u, alpha_); }

float CoatV2::mirror_reflectance(const Terms& t, float cos_o) const {
  return t.scale * fresnel_dielectric(cos_o, eta_);
}

}  // namespace torrance
