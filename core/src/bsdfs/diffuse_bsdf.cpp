#include "torrance/bsdfs/diffuse_bsdf.h"

#include "torrance/bsdfs/cosine_sampled.h"
#include "torrance/util/sampling.h"

namespace torrance {

DiffuseBsdf::DiffuseBsdf(const Vec3& color, float roughness, bool energy_preserving)
    : color_(glm::clamp(color, Vec3(0.0f), Vec3(1.0f))), energy_preserving_(energy_preserving) {
  if (energy_preserving_) eon_ = EnergyPreservingOrenNayar(color_, roughness);
  const float sigma = std::isfinite(roughness) ? clamp01(roughness) : 0.0f;
  a_ = 1.0f / (kPi + (3.0f * kPi - 4.0f) / 6.0f * sigma);
  b_ = sigma * a_;
}

// Cycles weighs wi by the cosine whatever side of the normal the viewer is on (a viewer below it
// counts as grazing: cos_o clamped to 0); that happens only about a Cycles 4.x DiffuseNormal.
LobeEval DiffuseBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  if (wi.z <= 0.0f) return {};
  if (energy_preserving_) return LobeEval{color_ * eon_.eval(wo, wi), Vec3(0.0f)};
  float t = 0.0f;
  if (b_ > 0.0f) {
    const float cos_o = std::max(wo.z, 0.0f);
    t = glm::dot(wi, wo) - wi.z * cos_o;
    if (t > 0.0f) t /= std::max(wi.z, cos_o);  // Cycles divides positive t only; negative t stays
  }
  LobeEval f;
  f.diffuse = color_ * (wi.z * (a_ + b_ * t));
  return f;
}

float DiffuseBsdf::pdf(const Vec3& /*wo*/, const Vec3& wi) const { return cosine_hemisphere_pdf(wi.z); }

BsdfSample DiffuseBsdf::sample(const Vec3& wo, float /*u_lobe*/, const Vec2& u) const {
  return sample_cosine_weighted(*this, wo, u);
}

}  // namespace torrance
