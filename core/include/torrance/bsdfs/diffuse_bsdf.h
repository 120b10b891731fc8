// The Diffuse BSDF node as Cycles 3.4 renders it: Lambert for Roughness 0, otherwise Cycles'
// Oren-Nayar variant (closure/bsdf_oren_nayar.h):
//
//   f cos = colour * cos_i * (A + B t),  A = 1 / (pi + (3 pi - 4) / 6 sigma),  B = sigma A,
//   t = wi.wo - cos_i cos_o, divided by max(cos_i, cos_o) where positive (Cycles keeps negative t
//   undivided),   sigma = Roughness clamped to [0, 1].
//
// (sigma = 0 gives A = 1/pi, B = 0: Lambert.) Sampled by the cosine (Cycles samples Oren-Nayar
// uniformly; the density differs, the expectation not). Everything it reflects is "diffuse" for
// the light passes. See bsdf.h for the conventions (eval includes the cosine).
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

class DiffuseBsdf {
 public:
  DiffuseBsdf(const Vec3& color, float roughness);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  // What a mixture samples it by: its colour's luminance.
  float sampling_albedo() const { return luminance(color_); }

 private:
  Vec3 color_;
  float a_, b_;
};

}  // namespace torrance
