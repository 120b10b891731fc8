// The (legacy) Hair BSDF node as Cycles 3.4 renders it (closure/bsdf_hair.h; unchanged in 4.2 and
// 5.3): Kajiya-Kay-like lobes about the strand, one closure per component.
//
// In the strand's frame (T the strand, locy = wo across the strand, locx = locy x T) the
// longitudinal angles are measured from the plane across the strand: theta_r of wo, theta_i of
// wi, and t = (theta_i + theta_r) / 2 - offset. Both components share the longitudinal density
//
//   M(t) = r1 / (2 (t^2 + r1^2) (a - b) cos theta_i),   a, b = atan((+-pi/2 + theta_r) / 2 - offset) / r1)
//
// (a Cauchy lobe about the tilted mirror direction, in solid angle); azimuthally, with phi the
// angle between wi and wo across the strand:
//   Reflection:   cos(phi / (2 r2)) / (4 r2) for phi < pi r2, else 0, around wo;
//   Transmission: r2 / (c ((pi - phi)^2 + r2^2)), c = 2 atan(pi / (2 r2)), around -wo (drawn
//                 within 90 degrees of it, evaluated beyond too).
// Roughness r1 = RoughnessU, r2 = RoughnessV, clamped to [0.001, 1].
//
// Cycles' eval is its pdf (eval = f cos = density; the colour is the closure weight), cut off
// where Reflection's wi lies below the normal or more than 90 degrees from wo across the strand,
// and where Transmission's lies above the normal; its sampled directions carry the weight Color
// whatever the cut-offs, and their pdf (for MIS) takes Reflection's azimuthal term as
// cos(phi / 2) / (4 r2) (its sampling's true density has phi / r2). Torrance renders the same:
//   eval(wo, wi) = Color x pdf(wo, wi)      pdf: Cycles' eval density, cut off as Cycles does;
//   sample: wi drawn as Cycles draws it, weight = Color, pdf = Cycles' sample pdf;
//   sampling_density(wo, wi): the density sample() really draws with (no cut-offs; the tests').
// In a mixture the sampled hair closure counts with its sample's own eval and pdf
// (MixtureBsdf::sample_mixture, as Cycles' surface_shader_bsdf_sample_closure).
//
// The strand's direction (`tangent`): the Tangent input when linked, else on curves the strand's
// direction (dPdu) and on meshes the triangle's second edge (dPdv, Offset then 0). Offset is the
// node's input negated, as Cycles' svm closure node takes it. Directions in the shading frame
// (z = N) as everywhere (bsdf.h); the tangent given in world space, turned by orient().
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

class HairBsdf {
 public:
  // offset: the node's Offset (radians), as given; tangent: a world direction (orient() follows).
  HairBsdf(const Vec3& color, bool transmission, float roughness_u, float roughness_v, float offset,
           const Vec3& tangent);
  // The world tangent given at construction into the shading frame.
  void orient(const Frame& frame);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  // The density sample() draws wi with (Cycles' formulas without its cut-offs).
  float sampling_density(const Vec3& wo, const Vec3& wi) const;
  // What a mixture samples it by: Cycles' sample weight, the colour's average.
  float sampling_albedo() const { return (color_.x + color_.y + color_.z) / 3.0f; }
  // Its samples count in a mixture with their own weight and pdf, not eval / pdf (see above).
  static constexpr bool kSampleIsOwnEval = true;

 private:
  struct View;  // wo in the strand's frame
  View at(const Vec3& wo) const;
  // Cycles' density at wi; `cut`: with its eval's cut-offs.
  float density(const View& v, const Vec3& wi, bool cut) const;

  Vec3 color_;
  bool transmission_;
  float r1_, r2_, offset_;
  Vec3 tangent_{1.0f, 0.0f, 0.0f};  // unit, in the shading frame
  Vec3 world_tangent_;
};

}  // namespace torrance
