// The Diffuse BSDF node as Cycles renders it: Lambert for Roughness 0, otherwise (Cycles 3.x-4.2)
// Cycles' Oren-Nayar variant (closure/bsdf_oren_nayar.h), or (energy_preserving, Cycles 4.3+) the
// energy-preserving Oren-Nayar of oren_nayar_eon.h with the node's colour as its albedo. 3.4's:
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
#include "torrance/bsdfs/oren_nayar_eon.h"

namespace torrance {

class DiffuseBsdf {
 public:
  DiffuseBsdf(const Vec3& color, float roughness, bool energy_preserving = false);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  // What a mixture samples it by: its colour's luminance.
  float sampling_albedo() const { return luminance(color_); }

 private:
  Vec3 color_;
  float a_, b_;
  bool energy_preserving_ = false;
  EnergyPreservingOrenNayar eon_;  // energy_preserving_ only
};

}  // namespace torrance
