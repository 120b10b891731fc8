#include "torrance/bsdfs/velvet_bsdf.h"

namespace torrance {

VelvetBsdf::VelvetBsdf(const Vec3& color, float sigma) : color_(glm::max(color, Vec3(0.0f))) {
  const float s = std::max(std::isfinite(sigma) ? clamp01(sigma) : 0.0f, 0.01f);
  inv_sigma2_ = 1.0f / (s * s);
}

LobeEval VelvetBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return {};
  const Vec3 sum = wo + wi;
  const float len2 = glm::dot(sum, sum);
  if (!(len2 > 0.0f)) return {};
  const Vec3 h = sum / std::sqrt(len2);
  const float cos_h = h.z, cos_oh = std::abs(glm::dot(wo, h));
  if (!(std::abs(cos_h) < 1.0f - 1e-5f) || !(cos_oh > 1e-5f)) return {};
  const float ratio = std::max(cos_h / cos_oh, 1e-5f);
  const float G = std::min(1.0f, 2.0f * ratio * std::min(wo.z, wi.z));
  const float sin2 = 1.0f - cos_h * cos_h;
  const float cot2 = cos_h * cos_h / sin2;
  const float D = std::exp(-cot2 * inv_sigma2_) * inv_sigma2_ * kInvPi / (sin2 * sin2);
  LobeEval f;
  f.diffuse = color_ * (0.25f * D * G / wo.z);
  return f;
}

float VelvetBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  return wo.z > 0.0f && wi.z > 0.0f ? 0.5f * kInvPi : 0.0f;
}

BsdfSample VelvetBsdf::sample(const Vec3& wo, float /*u_lobe*/, const Vec2& u) const {
  if (!(wo.z > 0.0f)) return {};
  const float z = u.x, r = safe_sqrt(1.0f - z * z), phi = kTwoPi * u.y;
  BsdfSample s;
  s.wi = Vec3(r * std::cos(phi), r * std::sin(phi), z);
  s.diffuse = true;
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f)) return {};
  s.weight = eval(wo, s.wi) / s.pdf;
  return s;
}

}  // namespace torrance
