#include "torrance/subsurface/exit_bsdf.h"

#include "torrance/bsdfs/cosine_sampled.h"
#include "torrance/bsdfs/principled_sheen.h"
#include "torrance/util/sampling.h"

namespace torrance {

LobeEval SubsurfaceExitBsdf::eval_lobes(const Vec3& /*wo*/, const Vec3& wi) const {
  if (wi.z <= 0.0f) return {};
  const float fresnel = fresnel_ ? 1.0f - 0.5f * schlick_weight(wi.z) : 1.0f;
  LobeEval f;
  f.diffuse = Vec3(kInvPi * fresnel * wi.z);
  return f;
}

float SubsurfaceExitBsdf::pdf(const Vec3& /*wo*/, const Vec3& wi) const { return cosine_hemisphere_pdf(wi.z); }

BsdfSample SubsurfaceExitBsdf::sample(const Vec3& wo, float /*u_lobe*/, const Vec2& u) const {
  return sample_cosine_weighted(*this, wo, u);
}

}  // namespace torrance
