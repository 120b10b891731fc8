// Equiangular sampling of a point on a ray segment toward a point on a light (Kulla and Fajardo
// 2012, "Importance Sampling Techniques for Path Tracing in Participating Media"): the point is
// drawn with density proportional to 1 / (D^2 + (t - delta)^2), i.e. uniform in the angle it
// subtends at the light, which cancels the inverse-square falloff of a small light seen from the
// ray. And the material/world Volume Sampling setting (Cycles' volume_sampling) that chooses,
// per medium, how a scattering point receiving direct light is found.
#pragma once

#include "torrance/util/math.h"

#include <cstdint>

namespace torrance {

// Cycles' Volume Sampling: Distance (free flight only, Torrance's way before), Equiangular (the
// direct light's point always equiangular), Multiple Importance (one of the two chosen with
// probability 1/2 per segment, power-heuristic weights).
enum class VolumeSampling : uint8_t { Distance, Equiangular, MultipleImportance };

// The method for a point inside several media at once (Cycles' volume_stack_sample_method): any
// Multiple Importance medium, or both Distance and Equiangular among them, gives Multiple
// Importance; otherwise the one they share. `none`: nothing combined yet.
struct VolumeSamplingCombiner {
  bool none = true;
  VolumeSampling method = VolumeSampling::Distance;
  void add(VolumeSampling m);
};

// A segment [tmin, tmax] (tmax may be infinite) of the ray origin + t dir (dir unit length),
// seen from light_point.
class EquiangularSegment {
 public:
  EquiangularSegment(const Vec3& origin, const Vec3& dir, const Vec3& light_point, float tmin, float tmax);
  // False: nothing can be drawn (an empty or invalid segment, an endless one the light lies on).
  bool valid() const { return valid_; }
  // The t of u in [0, 1) and its density; pdf 0 where !valid().
  float sample(float u, float& pdf) const;
  // The density of t (0 outside the segment).
  float pdf(float t) const;

 private:
  float tmin_ = 0.0f, tmax_ = 0.0f;
  float delta_ = 0.0f;  // the t closest to the light
  float d_ = 0.0f;      // the light's distance from the ray's line
  float theta_a_ = 0.0f, theta_b_ = 0.0f;
  bool uniform_ = false;  // the angle the segment subtends is too small: uniform in t instead
  bool valid_ = false;
};

}  // namespace torrance
