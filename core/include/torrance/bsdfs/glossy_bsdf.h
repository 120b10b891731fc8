// The Glossy BSDF node (distribution GGX) as Cycles 3.4 renders it (closure/bsdf_microfacet.h
// with no Fresnel), and 3.4's Anisotropic BSDF (4.x: the Glossy BSDF's Anisotropy): a pure GGX
// reflection lobe whose colour is a plain multiplier,
//
//   f cos = colour * D(h) G1(wo) G1(wi) / (4 cos_o),   alpha = Roughness^2,
//
// with the separable exact Smith G of microfacet.h. Anisotropy a (clamped to +-0.99, as Cycles)
// stretches the lobe along the tangent: alpha_x = alpha (1 - a), alpha_y = alpha / (1 - a) for
// a >= 0, alpha_x = alpha / (1 + a), alpha_y = alpha (1 + a) below, each at most 1; alpha_x lies
// along the tangent made perpendicular to the normal (orient(): the world tangent into the
// shading frame). Where alpha_x alpha_y is below ggx::kDeltaAlpha^2 (Cycles' 1e-7) it is a mirror
// (a delta lobe of reflectance colour). Sampled by visible normals; all "glossy" for the light
// passes. See bsdf.h for the conventions (eval includes the cosine).
//
// As Cycles 4.x (cycles4; the PRINCIPLED_V2 model's Blender): Smith's G is height-correlated,
// G2 = 1 / (1 + Lambda(wo) + Lambda(wi)), the mirror threshold is ggx_tables::kDeltaAlpha, and
// Multiscatter GGX (4.x's default distribution) is the single-scattering lobe scaled by
// 1 + F_ms (1 - E) / E (Kulla & Conty's albedo scaling with a constant Fresnel F = colour),
// E = E(r, wo.z) and E_avg(r) of ggx_tables.h at r = (alpha_x alpha_y)^(1/4).
//
// Beckmann (distribution): the same lobe with Beckmann's D and Cycles' rational Smith Lambda
// (beckmann.h), G separable (3.x) or height-correlated (4.x) as above, isotropic or anisotropic,
// sampled by Beckmann's visible normals (pdf: their exact density).
//
// Ashikhmin-Shirley (the same in 3.x, 4.x and 5.x): Cycles' Ashikhmin-Shirley lobe times the
// colour over the same alphas and tangent, each alpha clamped to [1e-4, 1] and a mirror where both
// are at most 1e-4 (ashikhmin_shirley.h), sampled by its half vectors.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/ggx_shape.h"
#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/microfacet_lobe.h"

namespace torrance {

class GlossyBsdf {
 public:
  // tangent: the world direction alpha_x lies along before the node's Rotation (turns about the
  // normal, counter-clockwise seen from its side, as Cycles' rotate_around_axis); zero, or with
  // anisotropy 0, the lobe is isotropic.
  GlossyBsdf(const Vec3& color, float roughness, float anisotropy = 0.0f, const Vec3& tangent = Vec3(0.0f),
             float rotation = 0.0f, bool cycles4 = false, bool multiscatter = false,
             MicrofacetDistribution distribution = MicrofacetDistribution::GGX);

  // The lobe's shape for Roughness, Anisotropy, the tangent and Rotation (turns), as above.
  static ggx::Shape lobe_shape(float roughness, float anisotropy, const Vec3& tangent, float rotation);

  // The lobe's axes in the shading frame the integrator evaluates it in: the tangent projected
  // onto the frame's plane (a tangent along the normal, or none: the frame's own x), turned by
  // the rotation.
  void orient(const Frame& frame) { lobe_.orient(frame); }

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;

  bool has_delta() const { return lobe_.is_delta(cycles4_ ? ggx_tables::kDeltaAlpha : ggx::kDeltaAlpha); }
  bool anisotropic() const { return lobe_.shape().anisotropic(); }
  // What a mixture samples it by: its colour's luminance.
  float sampling_albedo() const { return luminance(color_); }

 private:
  Vec3 color_;
  MicrofacetLobe lobe_;
  bool cycles4_ = false;
  float multiscatter_roughness_ = -1.0f;  // r of the albedo tables; < 0: single scattering
};

}  // namespace torrance
