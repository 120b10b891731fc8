// The Fournier-Forand phase function of oceanic particles (Cycles' closure/volume_fournier_forand.h;
// Fournier and Jonasz 1999), from the particles' relative IOR n and the backscattered fraction B:
// with x = sin^2(theta / 2) and delta = 4 x / (3 (n - 1)^2), the slope v of the particles' size
// distribution such that B comes out, and the closed form of the function and of its cumulative
// distribution (sampled by a safeguarded Newton iteration on the latter). Its forward peak is
// steep (most of it within 1e-3 rad for IORs near 1): both work in x, found from the directions
// as |wi + wo|^2 / 4, which keeps the angles that cos_theta = 1 in floats would lose.
#pragma once

#include "torrance/media/henyey_greenstein.h"

namespace torrance {

class FournierForandPhase {
 public:
  // Clamped as Cycles' setup: B to [0, 0.5 - 1e-3] (its magnitude), n to at least 1 + 1e-3.
  FournierForandPhase(float ior, float backscatter);

  float eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const { return eval(wo, wi); }
  PhaseSample sample(const Vec3& wo, const Vec2& u) const;

  // The phase function at x = sin^2(theta / 2), theta from the forward direction.
  double value(double x) const;
  // The fraction scattered within theta of the forward direction (0 at x = 0, 1 at x = 1).
  double cdf(double x) const;

 private:
  double n_ = 1.0, v_ = 0.0, c3_ = 0.0;
};

}  // namespace torrance
