#include "torrance/bsdfs/refraction_bsdf.h"

#include "torrance/bsdfs/outward.h"

namespace torrance {

namespace {

std::variant<GlassBsdf, PrincipledGlassV2> refraction_closure(const Vec3& color, float roughness, float ior,
                                                              bool beckmann, bool cycles4) {
  if (cycles4) return PrincipledGlassV2::refraction_node(roughness, ior, color, beckmann);
  return GlassBsdf(0.0f, roughness, ior, Vec3(0.0f), color, beckmann, /*refraction_only=*/true);
}

}  // namespace

RefractionBsdf::RefractionBsdf(const Vec3& color, float roughness, float ior, bool beckmann, bool cycles4)
    : color_(glm::max(color, Vec3(0.0f))), glass_(refraction_closure(color_, roughness, ior, beckmann, cycles4)) {}

LobeEval RefractionBsdf::eval_lobes(const Vec3& wo, const Vec3& wi, bool backfacing) const {
  LobeEval f;
  const Vec3 o = outward(wo, backfacing), i = outward(wi, backfacing);
  f.glossy = std::visit([&](const auto& g) { return g.eval(o, i); }, glass_);
  return f;
}

float RefractionBsdf::pdf(const Vec3& wo, const Vec3& wi, bool backfacing) const {
  return std::visit([&](const auto& g) { return g.pdf(outward(wo, backfacing), outward(wi, backfacing)); }, glass_);
}

BsdfSample RefractionBsdf::sample(const Vec3& wo, float u_lobe, const Vec2& u, bool backfacing) const {
  BsdfSample s = std::visit([&](const auto& g) { return g.sample(outward(wo, backfacing), u_lobe, u); }, glass_);
  s.wi = outward(s.wi, backfacing);
  return s;
}

}  // namespace torrance
