// Mie scattering by water droplets as Cycles approximates it (closure/volume_util.h,
// svm/closure.h; Jendersie and d'Eon 2023): a Henyey-Greenstein lobe (weight 1 - w) and a
// Draine lobe (weight w) whose parameters are fitted to the droplet diameter d in micrometres.
#pragma once

#include "torrance/media/draine_phase.h"

namespace torrance {

struct MieFit {
  float g_hg = 0.0f, g_draine = 0.0f, alpha = 0.0f, w = 0.0f;
};

// The fitted parameters at diameter d (micrometres; below 0 taken as 0).
MieFit mie_fit(float d);

class MiePhase {
 public:
  explicit MiePhase(float diameter);

  float eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const { return eval(wo, wi); }
  PhaseSample sample(const Vec3& wo, const Vec2& u) const;

 private:
  MieFit fit_;
  HenyeyGreenstein hg_;
  DrainePhase draine_;
};

}  // namespace torrance
