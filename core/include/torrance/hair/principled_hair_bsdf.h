// The Principled Hair BSDF (Chiang, Bitterli, Tappan and Burley 2016), as Cycles 3.4 renders it
// (closure/bsdf_hair_principled.h; the same model in Cycles 4.x as its "Chiang" variant): a
// dielectric cylinder with absorbing interior, its light leaving as R (reflection), TT
// (transmission), TRT and a residual TRRT+ lobe, each a longitudinal term M_p (a von Mises-Fisher
// lobe about the mirror direction, tilted by the cuticle scales) times an azimuthal one N_p (a
// trimmed logistic about the refracted direction) times an attenuation A_p (Fresnel and the
// absorption along the path inside):
//
//   eval(wo, wi) = sum_p A_p M_p N_p    (includes the cosine, bsdf.h),
//   sample: the lobe p by the shares |A_p| / sum_q |A_q| (|.|: the luminance), then theta by
//           M_p and phi by N_p (Cycles' formulas), theta tilted by the lobe's scale angle;
//   pdf(wo, wi)  = the density of those samples: sum_p share_p M_p N_p cos(theta'_p) / cos(theta_i),
//           theta'_p = theta_i untilted, M_p without Cycles' approximations of the Bessel
//           function I0. (Cycles' pdf is eval's sum: without the ratio, with the approximate
//           M_p, so its samples are weighted a little off their density; eval here is Cycles'.)
//
// The strand's frame (Cycles' setup): X along the strand, Y = X x wo, Z = X x Y, and h = the
// offset of the hit across the strand seen from wo (-1: grazing one edge, 0: the centre, 1: the
// other) = -N.Y with N the hit's normal (Cycles' round curves: Ng . (X x Z) with Ng = N; its
// ribbons: -v). Directions in the shading frame as everywhere (z = N, bsdf.h); `tangent` is the
// strand's direction in that frame. Nothing is one-sided: light leaves through both sides.
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

// Chiang's longitudinal lobe, shared with Huang's model (huang_hair_bsdf.h: its TRRT+ paths).
namespace chiang {
// M_p: the von Mises-Fisher lobe of variance v about the mirror of theta_o, as Cycles evaluates it
// (longitudinal_scattering: its I0 series and asymptote).
float longitudinal(float sin_i, float cos_i, float sin_o, float cos_o, float v);
// sin theta_i drawn by that lobe (exactly) from u in [0, 1)^2.
float sample_longitudinal_sin(const Vec2& u, float v, float sin_o, float cos_o);
}  // namespace chiang

// The node's inputs, reduced as Cycles' svm_node_closure_bsdf reduces them.
struct PrincipledHairParams {
  Vec3 sigma{0.0f};              // absorption coefficient (per unit of the strand's diameter)
  float roughness = 0.3f;        // longitudinal (Roughness)
  float radial_roughness = 0.3f; // azimuthal (Radial Roughness)
  float coat = 0.0f;             // Coat: R's roughness is (1 - coat) x the others'
  float ior = 1.55f;
  float offset = 0.0349066f;     // the cuticle scales' tilt (radians; Blender's default 2 degrees)
};

// Random Roughness and Random Color as Cycles' svm node applies them at each hit, for either
// model: with the strand's random r in [0, 1], the roughnesses times 1 + 2 (r - 0.5) Random
// Roughness and, for Melanin Concentration, the melanin times 1 + 2 (r - 0.5) Random Color
// (clamped to [0, 1]) before the absorption is made of it.
struct HairRandomness {
  enum class Coloring { Absorption, Melanin, DirectColor };
  Coloring coloring = Coloring::Absorption;
  Vec3 sigma{0.0f};  // Absorption Coefficient
  float melanin = 0.0f, melanin_redness = 0.0f;
  Vec3 color{1.0f};  // the Tint (Melanin) or the Color (Direct Coloring)
  float random_roughness = 0.0f, random_color = 0.0f;

  bool varies() const { return random_roughness != 0.0f || random_color != 0.0f; }
  // The absorption at a strand of random r; roughness and radial (the roughness the colour's
  // absorption is fitted with: Radial Roughness, or Huang's Roughness) scaled in place.
  Vec3 sigma_at(float r, float& roughness, float& radial) const;
};

class PrincipledHairBsdf {
 public:
  // tangent: the strand's direction in the frame eval, pdf and sample work in; or in world space,
  // with orient() to follow (a mixture's closures are made before the shading frame is known).
  PrincipledHairBsdf(const PrincipledHairParams& params, const Vec3& tangent);
  // The tangent given at construction, a world direction, into the shading frame.
  void orient(const Frame& frame);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  // What a mixture samples it by: Cycles' estimate of its albedo (bsdf_principled_hair_albedo).
  float sampling_albedo() const;

  // The Melanin Concentration parametrisation: sigma of eumelanin and pheomelanin amounts.
  static Vec3 sigma_from_concentration(float eumelanin, float pheomelanin);
  // The Direct Coloring parametrisation: the sigma whose multiple scattering looks `color`.
  static Vec3 sigma_from_reflectance(const Vec3& color, float radial_roughness);

 private:
  struct Strand;  // wo in the strand's frame and what follows from it
  Strand at(const Vec3& wo) const;
  Vec3 eval_at(const Strand& s, const Vec3& wi, float& pdf) const;

  Vec3 sigma_;
  float v_ = 0.0f;   // the longitudinal variance (TT: v / 4, TRT and beyond: 4 v)
  float s_ = 0.0f;   // the azimuthal logistic's scale
  float v_r_ = 0.0f; // R's variance (with the coat)
  float alpha_ = 0.0f;
  float eta_ = 1.55f;
  Vec3 tangent_;        // unit, in the shading frame
  Vec3 world_tangent_;  // as given
};

}  // namespace torrance
