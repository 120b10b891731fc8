// Sampling of a diffuse closure by the cosine about its frame's z: the direction, its density and
// eval / pdf as the weight (see bsdf.h), for closures whose directions are drawn so (Diffuse BSDF,
// the subsurface exit).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/util/sampling.h"

namespace torrance {

template <typename Closure>
BsdfSample sample_cosine_weighted(const Closure& closure, const Vec3& wo, const Vec2& u) {
  BsdfSample s;
  s.wi = sample_cosine_hemisphere(u);
  s.diffuse = true;
  s.pdf = closure.pdf(wo, s.wi);
  if (!(s.pdf > 0.0f)) return BsdfSample{};
  s.weight = closure.eval(wo, s.wi) / s.pdf;
  return s;
}

}  // namespace torrance
