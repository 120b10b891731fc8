// Rayleigh scattering (Cycles' closure/volume_rayleigh.h): p = 3 (1 + cos^2) / (16 pi), sampled
// by inverting its cumulative distribution in closed form (a cubic).
#pragma once

#include "torrance/media/henyey_greenstein.h"

namespace torrance {

class RayleighPhase {
 public:
  float eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const { return eval(wo, wi); }
  PhaseSample sample(const Vec3& wo, const Vec2& u) const;
};

float rayleigh(float cos_theta);

}  // namespace torrance
