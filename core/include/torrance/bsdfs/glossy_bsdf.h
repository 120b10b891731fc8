// The Glossy BSDF node (distribution GGX) as Cycles 3.4 renders it (closure/bsdf_microfacet.h
// with no Fresnel): a pure GGX reflection lobe whose colour is a plain multiplier,
//
//   f cos = colour * D(h) G1(wo) G1(wi) / (4 cos_o),   alpha = Roughness^2,
//
// with the separable exact Smith G of microfacet.h. Below ggx::kDeltaAlpha (Cycles' threshold)
// it is a mirror (a delta lobe of reflectance colour). Sampled by visible normals; all "glossy"
// for the light passes. See bsdf.h for the conventions (eval includes the cosine).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/microfacet.h"

namespace torrance {

class GlossyBsdf {
 public:
  GlossyBsdf(const Vec3& color, float roughness);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;

  bool has_delta() const { return alpha_ < ggx::kDeltaAlpha; }
  // What a mixture samples it by: its colour's luminance.
  float sampling_albedo() const { return luminance(color_); }

 private:
  Vec3 color_;
  float alpha_;
};

}  // namespace torrance
