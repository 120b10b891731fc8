// Dwivedi-guided flights of the subsurface random walk, as Cycles 3.4 mixes them in
// (integrator/subsurface_random_walk.h; Krivanek and d'Eon 2014, Meng et al. 2016, d'Eon and
// Krivanek 2020): directions drawn towards the entry's tangent plane (or, with an opposite side
// found, away from it) by the zero-variance "phase" p(cos) = 1 / (2 pi (v - cos) log((v+1)/(v-1)))
// of the diffusion length v, and flights stretched by 1 - cos / v, combined with the classic
// Henyey-Greenstein flights by the balance heuristic. Shorter walks; the same expectation.
#pragma once

#include "torrance/util/math.h"

#include <cmath>

namespace torrance {

struct DwivediGuide {
  float v = 1.0f;          // the diffusion length (> 1)
  float phase_log = 0.0f;  // log((v + 1) / (v - 1))

  // For the largest single-scattering albedo of the walk (d'Eon and Krivanek's eq. 67); v = 1
  // (no guide possible) where the albedo is too small.
  explicit DwivediGuide(float alpha) {
    v = 1.0f / std::sqrt(1.0f - std::pow(alpha, 2.44294f - 0.0215813f * alpha + 0.578637f / alpha));
    if (v > 1.0f) phase_log = std::log((v + 1.0f) / (v - 1.0f));
  }
  bool usable() const { return v > 1.0f && std::isfinite(v); }
  // The density of cos (per steradian, about the guide's axis).
  float pdf(float cos_theta) const { return 1.0f / ((v - cos_theta) * phase_log) * (0.5f / kPi); }
  float sample(float u) const { return v - (v + 1.0f) * std::exp(-u * phase_log); }
  // The flight's extinction stretch for a direction of cos about the axis.
  float stretch(float cos_theta) const { return 1.0f - cos_theta / v; }
};

}  // namespace torrance
