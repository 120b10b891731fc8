// The Metallic BSDF node (Blender 4.3+) as Cycles 4.x/5.x renders it (svm/closure.h's
// PHYSICAL_CONDUCTOR / F82_CONDUCTOR, closure/bsdf_microfacet.h): one GGX reflection lobe whose
// Fresnel is a metal's (metal_fresnel.h),
//
//   f cos = F(wo.h) D(h) G2(wo, wi) / (4 cos_o),   G2 = 1 / (1 + Lambda(wo) + Lambda(wi)),
//
// F either F82-tint (Base Color, Edge Tint) or a physical conductor (IOR n, Extinction k), alpha
// = Roughness^2 (Roughness and Anisotropy clamped to [0, 1]); Anisotropy stretches it as the
// Principled BSDF v2 does: alpha_x = alpha / s, alpha_y = alpha s, s = sqrt(1 - 0.9 Anisotropy)
// (each at most 1), along the tangent turned by Rotation (orient()). Multiscatter GGX (the node's
// default) scales the lobe by Kulla & Conty's 1 + F_ms (1 - E) / E with the Fresnel's mean fss
// (ggx_tables.h at (alpha_x alpha_y)^(1/4)). Below ggx_tables::kDeltaAlpha it is a mirror of
// reflectance F(wo.z). Sampled by visible normals; "glossy" for the light passes. Beckmann
// (beckmann): the same lobe with Beckmann's microfacets as Cycles evaluates them
// (microfacet_lobe.h), without multiscatter compensation (Cycles: Multiscatter GGX only). Thin
// Film (Blender 5.x, thin_film.h): F is the film's reflectance over the conductor (n, k), or for
// F82-tint over the conductor Gulbrandsen's fit gives for (Base Color, F(1/7)) with R23 the F82
// model refitted under the film, as Cycles 5.x;
// the multiscatter fss stays the film-less one (Cycles). A film flagged 4.x (ThinFilm::cycles5
// false: Cycles 4.x has no film on this node nor over conductors) is ignored.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/metal_fresnel.h"
#include "torrance/bsdfs/microfacet_lobe.h"

namespace torrance {

class MetallicBsdf {
 public:
  // conductor: first = n, second = k; else first = Base Color (f0), second = Edge Tint.
  MetallicBsdf(bool conductor, const Vec3& first, const Vec3& second, float roughness, float anisotropy = 0.0f,
               const Vec3& tangent = Vec3(0.0f), float rotation = 0.0f, bool multiscatter = false,
               const ThinFilm& film = ThinFilm{}, bool beckmann = false);

  void orient(const Frame& frame) { lobe_.orient(frame); }

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;

  Vec3 fresnel(float cos_i) const;
  bool has_delta() const;
  bool anisotropic() const { return lobe_.shape().anisotropic(); }
  // What a mixture samples it by: the luminance of its mean Fresnel.
  float sampling_albedo() const { return luminance(fss_); }

 private:
  bool conductor_ = false;
  Vec3 n_{0.0f}, k_{0.0f};  // the conductor's index
  F82Tint f82_;             // the F82-tint Fresnel, or the conductor's fit (for fss_)
  Vec3 fss_{0.0f};
  MicrofacetLobe lobe_;
  float multiscatter_roughness_ = -1.0f;  // r of the albedo tables; < 0: single scattering
  ThinFilm film_;                         // inactive: none (or not over conductors)
  Vec3 film_n_{0.0f}, film_k_{0.0f}, film_f82_{-1.0f};  // the conductor under the film (f82 < 0: exact)
};

}  // namespace torrance
