// Rough dielectric BSDF (glass): GGX microfacet reflection AND refraction, Walter et al. 2007
// ("Microfacet Models for Refraction through Rough Surfaces") -- the transmission side of the
// same Cook-Torrance model, as Cycles 3.4's GGX glass. Exact dielectric Fresnel, separable Smith G
// (G1(wo) G1(wi), like the PRINCIPLED reflection), alpha = roughness^2.
//
// Sides. The local frame's z is the surface's OUTWARD normal (not flipped towards wo): a direction
// with z > 0 is outside (IOR 1), z < 0 inside (IOR `ior`). The caller decides the side with the
// geometric normal and builds the frame from the unflipped shading normal. eta(w) below is the IOR
// on w's side; etap = eta(wi side) / eta(wo side) for transmission.
//
//   reflection   (wo, wi on one side)  h = normalize(wo + wi)
//       f = F(wo.h) D(h) G / (4 |cos_o| |cos_i|)
//   transmission (opposite sides)      h = normalize(eta_o wo + eta_i wi), turned to wo's side,
//                                      with wo.h > 0 > wi.h (else 0)
//       f = |wo.h| |wi.h| eta_i^2 (1 - F(wo.h)) D(h) G / (|cos_o| |cos_i| (eta_o wo.h + eta_i wi.h)^2)
//
// Convention for transmission: Walter's eq. 21 with eta_i^2 in the numerator, which is what Cycles
// 3.4 evaluates (bsdf_microfacet_ggx_eval_transmit: m_eta^2). It carries no radiance compression
// 1/etap^2 (pbrt's TransportMode::Radiance): the BSDF conserves energy flux,
//   integral of f |cos_i| dwi <= 1 (= 1 when smooth),
// and the generalised reciprocity reads  f(wo, wi) / eta_i^2 = f(wi, wo) / eta_o^2, i.e.
// f(wo, wi) / eta(wi)^2 is symmetric. (For a closed object the two conventions give the same image;
// they differ for a camera or light inside the medium.)
//
// Sampling: a visible normal of the GGX distribution seen from wo (wo's side), then reflection with
// probability F(wo.h) or refraction otherwise; weight = G1(wi) for both. pdf:
//   reflection   F G1(wo) D / (4 |cos_o|)
//   transmission (1 - F) G1(wo) D |wo.h| / |cos_o| * eta_i^2 |wi.h| / (eta_o wo.h + eta_i wi.h)^2
// (the last factor is Walter's Jacobian dh/dwi of refraction, eq. 17).
//
// Smooth limit: below ggx::kDeltaAlpha (the PRINCIPLED mirror threshold, Cycles' alpha^2 <= 1e-7)
// both lobes are deltas: a mirror with probability F and straight refraction otherwise, weight 1
// (times the colour); eval and pdf are 0. When |ior - 1| < 1e-4 (as Cycles) the interface is
// invisible: the ray passes straight through with weight 1.
// eval() includes |cos_i| (see bsdf.h); `color` multiplies both lobes (the Glass BSDF's Color).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/microfacet.h"

namespace torrance {

class RoughDielectricBsdf {
 public:
  RoughDielectricBsdf(float roughness, float ior, const Vec3& color = Vec3(1.0f));

  Vec3 eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;

  bool has_delta() const { return smooth_; }
  float alpha() const { return alpha_; }
  float ior() const { return eta_; }
  // Fresnel reflectance for wo at normal incidence on the macro surface (the smooth lobes' split).
  float mirror_reflectance(const Vec3& wo) const;

 private:
  // Everything eval and pdf share for one (wo, wi) pair; f_cos and pdf without the colour.
  struct Lobe {
    float f_cos = 0.0f, pdf = 0.0f;
  };
  Lobe evaluate(const Vec3& wo, const Vec3& wi) const;

  Vec3 color_;
  float alpha_, eta_;
  bool smooth_, invisible_;
};

}  // namespace torrance
