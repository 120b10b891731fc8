// Draine's phase function (Cycles' closure/volume_draine.h):
// p = (1 - g^2)(1 + alpha cos^2) / ((1 + alpha (1 + 2 g^2) / 3) 4 pi (1 + g^2 - 2 g cos)^(3/2)),
// Henyey-Greenstein's lobe times (1 + alpha cos^2), normalised. Sampled exactly by rejection from
// Henyey-Greenstein (acceptance (1 + alpha cos^2) / (1 + max(alpha, 0)), at least a third for
// the alpha of 250 that Mie's fit uses), its further random numbers from a stream seeded by u.
#pragma once

#include "torrance/media/henyey_greenstein.h"

namespace torrance {

class DrainePhase {
 public:
  // g clamped as Cycles' setup (|g| <= 1 - 1e-3); alpha >= -1 (clamped there) keeps it positive.
  DrainePhase(float g, float alpha);

  float eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const { return eval(wo, wi); }
  PhaseSample sample(const Vec3& wo, const Vec2& u) const;

  float value(float cos_theta) const;

 private:
  HenyeyGreenstein lobe_;
  float alpha_, norm_;
};

}  // namespace torrance
