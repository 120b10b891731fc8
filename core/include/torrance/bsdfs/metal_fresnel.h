// Fresnel reflectances of metals, as Cycles 4.x/5.x computes them (closure/bsdf_util.h):
//
// F82-tint (Kutz et al., "Novel aspects of the Adobe Standard Material", 2021): Schlick's curve
// from f0 with a dip near 82 degrees,
//   F(mu) = clamp(f0 + (1 - f0) (1 - mu)^5 - b mu (1 - mu)^6, 0, 1),
// b chosen so that F(1/7) = Schlick(1/7) * tint (b = 0 for a white tint); its cosine-weighted
// hemispherical mean is fss = f0 + (1 - f0) / 21 - b / 126. Principled v2's metal and the
// Metallic BSDF's default.
//
// A physical conductor of complex index n + ik against air (the Metallic BSDF's Physical
// Conductor): the exact unpolarised reflectance, the mean of the s and p ones; its fss is the
// F82 model fitted through F(1) and F(1/7), as Cycles estimates it, clamped to [0, 1].
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

struct F82Tint {
  F82Tint() = default;
  // f0 and tint clamped to [0, 1] per channel.
  F82Tint(const Vec3& f0, const Vec3& tint);
  // From the reflectances at mu = 1 and mu = 1/7 (the fit of a conductor).
  static F82Tint through(const Vec3& f0, const Vec3& f82);

  Vec3 eval(float cos_i) const;
  Vec3 fss() const { return glm::mix(f0, Vec3(1.0f), 1.0f / 21.0f) - b * (1.0f / 126.0f); }

  Vec3 f0{0.0f}, b{0.0f};
};

// Unpolarised reflectance of a conductor of index n + ik (per channel; n, k >= 0) at cos_i.
Vec3 conductor_fresnel(float cos_i, const Vec3& n, const Vec3& k);

}  // namespace torrance
