#include "torrance/media/henyey_greenstein.h"

#include <algorithm>
#include <cmath>

namespace torrance {

namespace {
constexpr float kInv4Pi = 0.25f / kPi;
constexpr float kIsotropic = 1e-3f;  // below this |g| Cycles treats the lobe as isotropic
}  // namespace

float henyey_greenstein(float cos_theta, float g) {
  if (std::abs(g) < kIsotropic) return kInv4Pi;
  const float denom = std::max(1.0f + g * g - 2.0f * g * cos_theta, 0.0f);
  return (1.0f - g * g) / (denom * std::sqrt(denom)) * kInv4Pi;
}

HenyeyGreenstein::HenyeyGreenstein(float g)
    : g_(std::isfinite(g) ? std::copysign(std::min(std::abs(g), 1.0f - kIsotropic), g) : 0.0f) {}

float HenyeyGreenstein::eval(const Vec3& wo, const Vec3& wi) const {
  return henyey_greenstein(glm::dot(-wo, wi), g_);
}

PhaseSample HenyeyGreenstein::sample(const Vec3& wo, const Vec2& u) const {
  // Cycles' inversion, cos_theta = (1 + g^2 - k^2) / 2g, written as 1 - cos_theta and 1 + cos_theta
  // so that a narrow lobe keeps its precision next to its peak.
  float one_minus_cos, one_plus_cos;
  if (std::abs(g_) < kIsotropic) {
    one_minus_cos = 2.0f * u.x;
    one_plus_cos = 2.0f - 2.0f * u.x;
  } else {
    const float k = (1.0f - g_ * g_) / (1.0f - g_ + 2.0f * g_ * u.x);
    one_minus_cos = std::clamp((k * k - (1.0f - g_) * (1.0f - g_)) / (2.0f * g_), 0.0f, 2.0f);
    one_plus_cos = std::clamp(((1.0f + g_) * (1.0f + g_) - k * k) / (2.0f * g_), 0.0f, 2.0f);
  }
  const float cos_theta = one_minus_cos < one_plus_cos ? 1.0f - one_minus_cos : one_plus_cos - 1.0f;
  const float sin_theta = safe_sqrt(one_minus_cos * one_plus_cos);
  const float phi = 2.0f * kPi * u.y;
  const Frame around(-wo);
  PhaseSample s;
  s.wi = glm::normalize(around.to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta)));
  s.pdf = henyey_greenstein(cos_theta, g_);
  return s;
}

}  // namespace torrance
