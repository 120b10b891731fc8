// The Translucent BSDF node as Cycles renders it (closure/bsdf_diffuse.h, the same in 3.4 and
// 5.x): Lambertian transmission to the side of the surface away from the viewer,
//
//   f cos = colour * max(-cos_i, 0) / pi,
//
// with the viewer's side z > 0 (the shading frame turned towards it, bsdf.h) and light from
// z < 0. Sampled by the cosine about -z (pdf max(-cos_i, 0) / pi, so every sample's weight is
// the colour). Everything it passes is "diffuse" (Cycles' LABEL_TRANSMIT | LABEL_DIFFUSE).
// A mixture holding it transmits (MixtureBsdf::transmits): the integrator then lets light
// through the geometric surface where the geometric and shading normals agree on the side.
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

class TranslucentBsdf {
 public:
  explicit TranslucentBsdf(const Vec3& color);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  // What a mixture samples it by: its colour's luminance.
  float sampling_albedo() const { return luminance(color_); }

 private:
  Vec3 color_;
};

}  // namespace torrance
