// The Glossy (and 3.x Anisotropic) BSDF node with Blender 3.x's Multiscatter GGX distribution, as
// Cycles 3.4 renders it (its CLOSURE_BSDF_MICROFACET_MULTI_GGX_ID): the random walk of
// microsurface_walk.h with the node's colour c at every bounce, times c (the closure's weight),
// alpha = Roughness^2 stretched by Anisotropy as the GGX Glossy's (GlossyBsdf::lobe_shape); a
// mirror of reflectance c below ggx::kDeltaAlpha. Its eval is an estimate and its sample's
// weight is not eval / pdf: a mixture counts its sample as its own eval (kSampleIsOwnEval).
// Blender 4.x/5.x's Multiscatter GGX is GlossyBsdf's albedo scaling instead.
#pragma once

#include "torrance/bsdfs/glossy_bsdf.h"
#include "torrance/bsdfs/microsurface_walk.h"

namespace torrance {

class MultiscatterGlossyBsdf {
 public:
  static constexpr bool kSampleIsOwnEval = true;

  MultiscatterGlossyBsdf(const Vec3& color, float roughness, float anisotropy = 0.0f,
                         const Vec3& tangent = Vec3(0.0f), float rotation = 0.0f,
                         microsurface::HeightStep step = microsurface::HeightStep::Cycles);

  void orient(const Frame& frame) { walk_.orient(frame); }
  bool anisotropic() const { return walk_.shape().anisotropic(); }
  bool has_delta() const { return walk_.has_delta(); }

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const {
    LobeEval f;
    f.glossy = color_ * walk_.eval(wo, wi);
    return f;
  }
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const { return walk_.pdf(wo, wi); }
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const {
    BsdfSample s = walk_.sample(wo, u_lobe, u);
    s.weight *= color_;
    return s;
  }

  float sampling_albedo() const { return luminance(color_); }

 private:
  Vec3 color_;
  microsurface::Walk walk_;
};

}  // namespace torrance
