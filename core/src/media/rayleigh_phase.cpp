#include "torrance/media/rayleigh_phase.h"

#include "torrance/media/phase_function.h"

#include <algorithm>
#include <cmath>

namespace torrance {

float rayleigh(float cos_theta) { return 3.0f / (16.0f * kPi) * (1.0f + cos_theta * cos_theta); }

float RayleighPhase::eval(const Vec3& wo, const Vec3& wi) const { return rayleigh(glm::dot(-wo, wi)); }

PhaseSample RayleighPhase::sample(const Vec3& wo, const Vec2& u) const {
  // The cdf over cos_theta is (c^3 + 3c + 4) / 8 = u: the depressed cubic c^3 + 3c - 2b = 0 with
  // b = 4u - 2, whose real root (Cardano) is w - 1/w, w = cbrt(b + sqrt(b^2 + 1)); taken on the
  // side where nothing cancels and mirrored.
  const float b = 4.0f * u.x - 2.0f;
  const float w = std::cbrt(std::abs(b) + std::sqrt(b * b + 1.0f));
  const float cos_theta = std::clamp(std::copysign(w - 1.0f / w, b), -1.0f, 1.0f);
  PhaseSample s;
  s.wi = phase_direction(wo, cos_theta, u.y);
  s.pdf = rayleigh(cos_theta);
  return s;
}

}  // namespace torrance
