#include "torrance/bsdfs/metal_fresnel.h"

namespace torrance {

namespace {
constexpr float kF = 6.0f / 7.0f;                   // 1 - mu at mu = 1/7
constexpr float kF6 = kF * kF * kF * kF * kF * kF;  // (1 - mu)^6 there; (1 - mu)^5 = kF6 / kF
}  // namespace

F82Tint::F82Tint(const Vec3& f0_in, const Vec3& tint_in) : f0(glm::min(f0_in, Vec3(1.0f))) {
  const Vec3 tint = glm::min(tint_in, Vec3(1.0f));
  if (tint != Vec3(1.0f)) {
    const Vec3 schlick_82 = glm::mix(f0, Vec3(1.0f), kF6 / kF);
    b = schlick_82 * (7.0f / kF6) * (Vec3(1.0f) - tint);
  }
}

F82Tint F82Tint::through(const Vec3& f0, const Vec3& f82) {
  F82Tint t;
  t.f0 = f0;
  t.b = (7.0f / kF6) * (glm::mix(f0, Vec3(1.0f), kF6 / kF) - f82);
  return t;
}

Vec3 F82Tint::eval(float cos_i) const {
  const float c = clamp01(cos_i), mu = 1.0f - c;
  const float mu5 = (mu * mu) * (mu * mu) * mu;
  const Vec3 schlick = glm::mix(f0, Vec3(1.0f), mu5);
  return glm::clamp(schlick - b * (c * mu5 * mu), Vec3(0.0f), Vec3(1.0f));
}

namespace {
// The s and p reflectances' mean for one channel (the standard closed form, e.g. Born & Wolf).
float conductor_channel(float cos_i, float n, float k) {
  const float c = clamp01(cos_i), c2 = c * c, s2 = 1.0f - c2;
  const float t0 = n * n - k * k - s2;
  const float a2b2 = std::sqrt(t0 * t0 + 4.0f * n * n * k * k);
  const float a = std::sqrt(std::max(0.5f * (a2b2 + t0), 0.0f));
  const float t1 = a2b2 + c2, t2 = 2.0f * a * c;
  const float rs = (t1 - t2) / std::max(t1 + t2, 1e-20f);
  const float t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
  const float rp = rs * (t3 - t4) / std::max(t3 + t4, 1e-20f);
  return clamp01(0.5f * (rs + rp));
}
}  // namespace

Vec3 conductor_fresnel(float cos_i, const Vec3& n, const Vec3& k) {
  return Vec3(conductor_channel(cos_i, n.x, k.x), conductor_channel(cos_i, n.y, k.y),
              conductor_channel(cos_i, n.z, k.z));
}

}  // namespace torrance
