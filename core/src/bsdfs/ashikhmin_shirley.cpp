#include "torrance/bsdfs/ashikhmin_shirley.h"

#include "torrance/bsdfs/microfacet.h"  // reflection_half, reflect

#include <algorithm>
#include <cmath>

namespace torrance::ashikhmin_shirley {

namespace {

constexpr float kFloor = 1e-6f;

// p_h with the exponents at hand: the isotropic form when they are equal (as Cycles chooses).
// (h.z)^e as exp(e ln h.z), ln h.z from sin^2 so that it stays accurate near the normal.
float half_vector_density(const Vec3& h, float n_x, float n_y) {
  const float x2 = h.x * h.x, y2 = h.y * h.y, sin2 = x2 + y2;
  const float log_cos = h.z > kFloor ? 0.5f * std::log1p(-std::min(sin2, 1.0f)) : std::log(kFloor);
  if (n_x == n_y) return (n_x + 1.0f) / kTwoPi * std::exp(n_x * log_cos);
  const float e = sin2 > 0.0f ? (n_x * x2 + n_y * y2) / sin2 : 0.0f;
  return std::sqrt((n_x + 1.0f) * (n_y + 1.0f)) / kTwoPi * std::exp(e * log_cos);
}

// The paper's azimuth of a half vector in the first quadrant for u in [0, 1].
float first_quadrant_phi(float n_x, float n_y, float u) {
  return std::atan(std::sqrt((n_x + 1.0f) / (n_y + 1.0f)) * std::tan(0.5f * kPi * u));
}

}  // namespace

float exponent(float alpha) {
  const float a = std::clamp(alpha, kMinAlpha, 1.0f);
  return 2.0f / (a * a) - 2.0f;
}

float half_vector_pdf(const Vec3& h, float alpha_x, float alpha_y) {
  if (!(h.z > 0.0f)) return 0.0f;
  return half_vector_density(h, exponent(alpha_x), exponent(alpha_y));
}

float eval(const Vec3& wo, const Vec3& wi, float alpha_x, float alpha_y) {
  if (!(wo.z > 0.0f && wi.z > 0.0f) || is_mirror(alpha_x, alpha_y)) return 0.0f;
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return 0.0f;
  const float o_h = std::max(std::abs(glm::dot(h, wo)), kFloor);
  const float quarter_p = 0.25f * half_vector_density(h, exponent(alpha_x), exponent(alpha_y));
  return std::max(wi.z, kFloor) * quarter_p / std::max(o_h * std::max(wo.z, wi.z), kFloor);
}

float pdf(const Vec3& wo, const Vec3& wi, float alpha_x, float alpha_y) {
  if (!(wo.z > 0.0f && wi.z > 0.0f) || is_mirror(alpha_x, alpha_y)) return 0.0f;
  Vec3 h;
  if (!ggx::reflection_half(wo, wi, h)) return 0.0f;
  const float o_h = std::max(std::abs(glm::dot(h, wo)), kFloor);
  return 0.25f * half_vector_density(h, exponent(alpha_x), exponent(alpha_y)) / o_h;
}

Vec3 sample_half_vector(float alpha_x, float alpha_y, const Vec2& u) {
  const float n_x = exponent(alpha_x), n_y = exponent(alpha_y);
  float phi, e = n_x;
  if (n_x == n_y) {
    phi = kTwoPi * u.x;
  } else {
    // The quadrant from u.x, the rest of u.x (mirrored in the second and fourth, so that phi
    // runs on continuously) the azimuth within it.
    const float v = 4.0f * std::clamp(u.x, 0.0f, 1.0f);
    const int quadrant = std::min(int(v), 3);
    const float t = quadrant % 2 ? float(quadrant + 1) - v : v - float(quadrant);
    const float p = first_quadrant_phi(n_x, n_y, t);
    phi = quadrant == 0 ? p : quadrant == 1 ? kPi - p : quadrant == 2 ? kPi + p : kTwoPi - p;
    const float c = std::cos(p), s = std::sin(p);
    e = n_x * c * c + n_y * s * s;
  }
  // cos theta = u^(1 / (e + 1)); 1 - cos theta by expm1, accurate for the sharpest lobes.
  const float log_cos = std::log(u.y) / (e + 1.0f);
  const float cos_t = std::exp(log_cos);
  const float sin_t = std::sqrt(std::max(0.0f, -std::expm1(log_cos) * (1.0f + cos_t)));
  return Vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
}

Vec3 sample(const Vec3& wo, float alpha_x, float alpha_y, const Vec2& u) {
  return ggx::reflect(wo, sample_half_vector(alpha_x, alpha_y, u));
}

}  // namespace torrance::ashikhmin_shirley
