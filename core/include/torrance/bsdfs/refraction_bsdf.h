// The Refraction BSDF node as Cycles renders it (svm/closure.h with
// bsdf_microfacet_*_refraction / bsdf_refraction): the refraction half of the Glass BSDF node
// (glass.h) alone, with no Fresnel and no reflection, weighted by Color,
//
//   f |cos_i| = colour * G1(wo) G1(wi) D(h) etap^2 |wo.h| |wi.h| / (|cos_o| (wo.h + etap wi.h)^2),
//
// alpha = Roughness^2 (GGX, or Beckmann with Cycles' D and G1), a straight refraction (a delta)
// below ggx::kDeltaAlpha and for the Sharp distribution, etap = IOR of wi's side / IOR of wo's.
// Light leaving on the viewer's side is not reflected: the surface is dark there. Sampled as the
// glass's refraction lobe; a microfacet at total internal reflection gives no sample (Cycles too).
//
// Frames as MixtureBsdf's closures: wo.z > 0 (the shading frame turned towards the viewer),
// `backfacing` the viewer behind the geometric surface (inside, IOR `ior`); the glass is
// evaluated in its outward frame. Its light is "glossy" (as the glass's, LobeEval).
//
// As Cycles 4.x/5.x (cycles4): the one microfacet closure of principled_glass_v2.h without Fresnel
// or reflection (PrincipledGlassV2::refraction_node): Smith's G height-correlated, Beckmann's
// normals drawn by visible normals.
#pragma once

#include "torrance/bsdfs/glass.h"
#include "torrance/bsdfs/outward.h"
#include "torrance/bsdfs/principled_glass_v2.h"

#include <variant>

namespace torrance {

class RefractionBsdf {
 public:
  RefractionBsdf(const Vec3& color, float roughness, float ior, bool beckmann, bool cycles4 = false);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi, bool backfacing) const;
  float pdf(const Vec3& wo, const Vec3& wi, bool backfacing) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u, bool backfacing) const;
  bool connects(const Vec3& wo, const Vec3& wi, bool backfacing) const {  // GlassBsdf::connects
    return std::visit([&](const auto& g) { return g.connects(outward(wo, backfacing), outward(wi, backfacing)); },
                      glass_);
  }
  // What a mixture samples it by: its colour's luminance.
  float sampling_albedo() const { return luminance(color_); }

 private:
  Vec3 color_;
  std::variant<GlassBsdf, PrincipledGlassV2> glass_;  // Cycles 3.x's closure, or 4.x/5.x's
};

}  // namespace torrance
