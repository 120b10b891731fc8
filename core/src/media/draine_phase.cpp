#include "torrance/media/draine_phase.h"

#include "torrance/util/sampling.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace torrance {

namespace {

constexpr int kMaxTries = 256;  // each accepted with probability >= 1 / (1 + alpha) x its norm

uint32_t bits(float x) {
  uint32_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

}  // namespace

DrainePhase::DrainePhase(float g, float alpha)
    : lobe_(g), alpha_(std::isfinite(alpha) ? std::max(alpha, -1.0f) : 0.0f) {
  const float g_clamped = lobe_.g();
  norm_ = 1.0f / (1.0f + alpha_ * (1.0f + 2.0f * g_clamped * g_clamped) / 3.0f);
}

float DrainePhase::value(float cos_theta) const {
  return henyey_greenstein(cos_theta, lobe_.g()) * (1.0f + alpha_ * cos_theta * cos_theta) * norm_;
}

float DrainePhase::eval(const Vec3& wo, const Vec3& wi) const { return value(glm::dot(-wo, wi)); }

PhaseSample DrainePhase::sample(const Vec3& wo, const Vec2& u) const {
  const float bound = 1.0f + std::max(alpha_, 0.0f);
  Rng rng(bits(u.x), bits(u.y), 0xd2a1e5u);
  Vec2 v = u;
  PhaseSample s;
  for (int n = 0; n < kMaxTries; ++n) {
    s = lobe_.sample(wo, v);
    const float c = glm::dot(-wo, s.wi);
    if (rng.next_1d() * bound < 1.0f + alpha_ * c * c) break;
    v = Vec2(rng.next_1d(), u.y);
  }
  s.pdf = eval(wo, s.wi);
  return s;
}

}  // namespace torrance
