// The BSDF a subsurface walk's exit point shades with (Cycles 3.4's subsurface_shader_data_setup):
// white Lambert for the Subsurface Scattering node; for the Principled BSDF Cycles' Lambert exit
// (the light side of Burley's diffuse Fresnel), f cos = (1 - F_L / 2) cos_i / pi with
// F_L = (1 - cos_i)^5. Sampled by the cosine; all of it "diffuse" for the light passes.
// See bsdf.h for the conventions (eval includes the cosine).
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

class SubsurfaceExitBsdf {
 public:
  explicit SubsurfaceExitBsdf(bool fresnel) : fresnel_(fresnel) {}

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  float sampling_albedo() const { return 1.0f; }

 private:
  bool fresnel_;
};

}  // namespace torrance
