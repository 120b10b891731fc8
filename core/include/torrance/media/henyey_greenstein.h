// The Henyey-Greenstein phase function of Cycles' Volume Scatter and Principled Volume
// (closure/volume.h): a density over the sphere of directions, so eval and pdf are one value and
// sample() importance-samples it exactly (its weight is 1). wo points from the scattering point
// towards where the light goes (the viewer), as a BSDF's wo; wi towards where it comes from.
#pragma once

#include "torrance/util/math.h"

namespace torrance {

struct PhaseSample {
  Vec3 wi{0.0f};
  float pdf = 0.0f;  // per steradian; eval(wo, wi) equals it
  bool valid() const { return pdf > 0.0f; }
};

class HenyeyGreenstein {
 public:
  // g in (-1, 1): Cycles clamps |g| to 1 - 1e-3 (a delta lobe is not a phase function it samples).
  explicit HenyeyGreenstein(float g);

  float g() const { return g_; }
  // The phase function's value (1/sr) between a path that arrived travelling along -wo and goes on
  // along wi (Cycles' cos_theta = dot(-I, omega_in)).
  float eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const { return eval(wo, wi); }
  PhaseSample sample(const Vec3& wo, const Vec2& u) const;

 private:
  float g_;
};

// The phase function's value at cos_theta, the cosine between the direction a path arrived
// travelling in and the one it goes on in.
float henyey_greenstein(float cos_theta, float g);

}  // namespace torrance
