// The Toon BSDF node as Cycles 3.4 renders it (closure/bsdf_toon.h): a flat lobe of Size x 90
// degrees about an axis, fading linearly to nothing over a further Smooth x 90 degrees,
//
//   f cos = colour * I(angle) / (2 pi (1 - cos theta_s)),   theta_s = min(size + smooth, 90 deg),
//   I = 1 below size, 1 - (angle - size) / smooth up to size + smooth, else 0,
//
// (size, smooth: the inputs clamped to [0, 1], times 90 degrees). Diffuse: the axis is the
// normal, angle that of wi to it, and wi above the surface ("diffuse" light). Glossy: the axis
// is wo mirrored about the normal, both directions above the surface ("glossy" light). Neither
// has the cosine of wi: a Toon of Smooth 0 reflects exactly its colour whatever its Size (the
// glossy one less where its cone dips below the horizon).
//
// Sampled uniformly within the cone of half-angle theta_s about the axis (pdf 1 / its solid
// angle) from (u_1, u_2) as Cycles' sample_uniform_cone does:
//   Cycles 3.x:  1 - cos theta = (1 - u_1) (1 - cos theta_s), phi = 2 pi u_2;
//   Cycles 4.x:  1 - cos theta = r^2 (1 - cos theta_s), (r, phi) the concentric map of (u_1, u_2).
// Blender 3.x's samples are weighted as Cycles 3.4 weighs them, colour * I(theta_s u_1): the
// fade at theta_s times u_1, not at the direction's own angle, so that its BSDF-sampled light is
// faded differently from its evaluated (light-sampled) light; Torrance renders the same blend
// (Smooth 0.3-0.4 Toons in Blender 3.4: block mean 0.0122 with eval / pdf, 0.0064 with this,
// Cycles' own 0.0071). Blender 4.x's are weighted eval / pdf: Cycles 4.2's and 5.3's images
// agree with that (block mean 0.0082, Cycles' own 0.0093), not with 3.4's weight (0.0146) nor
// with the fade at theta_s u_1 about the concentric mapping, as 4.x's bsdf_toon.h reads (0.0158).
// With Smooth 0 all are eval / pdf. A mixture of several closures weighs its samples by eval /
// pdf of the whole (mixture_bsdf.h): there the Toon is the evaluated one.
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

class ToonBsdf {
 public:
  // cycles4: Blender 4.x's Toon (Cycles 4.x's cone sampling, weights eval / pdf), else 3.x's.
  ToonBsdf(const Vec3& color, float size, float smooth, bool glossy, bool cycles4 = false);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  // What a mixture samples it by: its colour's luminance.
  float sampling_albedo() const { return luminance(color_); }

 private:
  // The cosine of wi's angle to the lobe's axis for this wo; false where the lobe is empty.
  bool axis_cosine(const Vec3& wo, const Vec3& wi, float& cos_angle) const;
  float intensity(float angle) const;

  Vec3 color_;
  float size_, smooth_;      // radians
  float one_minus_cos_cone_;  // of theta_s
  float cone_pdf_;            // 1 / the cone's solid angle (0: an empty lobe)
  bool glossy_, cycles4_;
};

}  // namespace torrance
