#include "torrance/bsdfs/refraction_bsdf.h"

#include "torrance/bsdfs/outward.h"

namespace torrance {

RefractionBsdf::RefractionBsdf(const Vec3& color, float roughness, float ior, bool beckmann)
    : color_(glm::max(color, Vec3(0.0f))),
      glass_(0.0f, roughness, ior, Vec3(0.0f), color_, beckmann, /*refraction_only=*/true) {}

LobeEval RefractionBsdf::eval_lobes(const Vec3& wo, const Vec3& wi, bool backfacing) const {
  LobeEval f;
  f.glossy = glass_.eval(outward(wo, backfacing), outward(wi, backfacing));
  return f;
}

float RefractionBsdf::pdf(const Vec3& wo, const Vec3& wi, bool backfacing) const {
  return glass_.pdf(outward(wo, backfacing), outward(wi, backfacing));
}

BsdfSample RefractionBsdf::sample(const Vec3& wo, float u_lobe, const Vec2& u, bool backfacing) const {
  BsdfSample s = glass_.sample(outward(wo, backfacing), u_lobe, u);
  s.wi = outward(s.wi, backfacing);
  return s;
}

}  // namespace torrance
