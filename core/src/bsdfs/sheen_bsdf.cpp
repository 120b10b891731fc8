#include "torrance/bsdfs/sheen_bsdf.h"

#include "torrance/util/sampling.h"
#include "torrance/bsdfs/sheen_ltc_table.h"

namespace torrance {

SheenBsdf::SheenBsdf(const Vec3& color, float roughness)
    : color_(glm::max(color, Vec3(0.0f))),
      roughness_(std::min(std::max(std::isfinite(roughness) ? roughness : 0.0f, 1e-3f), 1.0f)) {}

float SheenBsdf::sampling_albedo() const { return luminance(color_) * sheen_ltc::lookup(1.0f, roughness_).albedo; }

SheenBsdf::Lobe SheenBsdf::lobe_at(float cos_o) const {
  Lobe l;
  if (!(cos_o > 0.0f) || !std::isfinite(cos_o)) return l;
  const sheen_ltc::Coefficients c = sheen_ltc::lookup(cos_o, roughness_);
  if (!(c.a > 0.0f) || !(c.albedo > 0.0f)) return l;  // the table's empty corner (smooth, not grazing)
  l.a = c.a;
  l.b = c.b;
  l.weight = color_ * c.albedo;
  return l;
}

SheenBsdf::Lobe SheenBsdf::oriented(Lobe l, const Vec3& wo) {
  if (!is_finite(wo)) return Lobe{};
  // x: wo's tangential direction (any tangent at normal incidence, where the lobe is symmetric).
  const float t2 = wo.x * wo.x + wo.y * wo.y;
  l.x = t2 > 1e-12f ? Vec3(wo.x, wo.y, 0.0f) / std::sqrt(t2) : Vec3(1.0f, 0.0f, 0.0f);
  l.y = Vec3(-l.x.y, l.x.x, 0.0f);
  return l;
}

float SheenBsdf::Lobe::density(const Vec3& wi) const {
  const float u = a * glm::dot(x, wi) + b * wi.z, v = a * glm::dot(y, wi);
  const float k = a / (u * u + v * v + wi.z * wi.z);
  return wi.z * kInvPi * k * k;
}

Vec3 SheenBsdf::Lobe::sample(const Vec2& u) const {
  const Vec2 d = sample_concentric_disk(u);
  const float dz = safe_sqrt(1.0f - glm::dot(d, d));
  const Vec3 local = glm::normalize(Vec3((d.x - dz * b) / a, d.y / a, dz));
  return local.x * x + local.y * y + Vec3(0.0f, 0.0f, local.z);
}

LobeEval SheenBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  if (!(wi.z > 0.0f)) return {};
  const Lobe l = lobe(wo);
  if (!l.reflects()) return {};
  LobeEval f;
  f.diffuse = l.weight * l.density(wi);
  return f;
}

float SheenBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  if (!(wi.z > 0.0f)) return 0.0f;
  const Lobe l = lobe(wo);
  return l.reflects() ? l.density(wi) : 0.0f;
}

BsdfSample SheenBsdf::sample(const Vec3& wo, float /*u_lobe*/, const Vec2& u) const {
  const Lobe l = lobe(wo);
  if (!l.reflects()) return {};
  BsdfSample s;
  s.wi = l.sample(u);
  if (!(s.wi.z > 0.0f)) return {};
  s.diffuse = true;
  s.pdf = l.density(s.wi);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf)) return {};
  s.weight = l.weight;  // f cos / pdf: D cancels
  return s;
}

}  // namespace torrance
