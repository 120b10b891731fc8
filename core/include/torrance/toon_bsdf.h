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
// angle, as Cycles' samples), each sample weighted by I at its own angle. Cycles 3.4 weighs its
// sampled directions by I at the angle theta_s u_1 instead (u_1 the random number that also
// chose their cos theta), the same as here with Smooth 0 but a differently faded lobe otherwise;
// its evaluation (light sampling) is the formula above, as here.
#pragma once

#include "torrance/bsdf.h"

namespace torrance {

class ToonBsdf {
 public:
  ToonBsdf(const Vec3& color, float size, float smooth, bool glossy);

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
  bool glossy_;
};

}  // namespace torrance
