#include "torrance/bsdfs/translucent_bsdf.h"

#include "torrance/util/sampling.h"

namespace torrance {

TranslucentBsdf::TranslucentBsdf(const Vec3& color) : color_(glm::max(color, Vec3(0.0f))) {}

LobeEval TranslucentBsdf::eval_lobes(const Vec3& /*wo*/, const Vec3& wi) const {
  LobeEval f;
  if (wi.z < 0.0f) f.diffuse = color_ * (-wi.z * kInvPi);
  return f;
}

float TranslucentBsdf::pdf(const Vec3& /*wo*/, const Vec3& wi) const { return cosine_hemisphere_pdf(-wi.z); }

BsdfSample TranslucentBsdf::sample(const Vec3& wo, float /*u_lobe*/, const Vec2& u) const {
  BsdfSample s;
  s.wi = sample_cosine_hemisphere(u);
  s.wi.z = -s.wi.z;
  s.diffuse = true;
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f)) return BsdfSample{};
  s.weight = color_;
  return s;
}

}  // namespace torrance
