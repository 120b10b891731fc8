// Blender 4.3+'s Gabor Texture as Cycles computes it: see shader_gabor.h.
#include "torrance/shader/shader_gabor.h"

#include "torrance/shader/shader_hash.h"

#include <cmath>

namespace torrance::shader {

namespace {

constexpr int kImpulsesPerCell = 8;

// Cycles' dot products and lengths: components summed left to right.
inline float dot2(const Vec2& a, const Vec2& b) { return a.x * b.x + a.y * b.y; }
inline float dot3(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// The windowed Gaussian at squared distance d2 from an impulse's centre: exp(-pi d2) under a Hann
// window (0 at d2 = 1).
inline float windowed_gaussian(float d2) {
  const float hann = 0.5f + 0.5f * std::cos(kPi * d2);
  return std::exp(-kPi * d2) * hann;
}

// envelope * (cos angle, sin angle) with angle = 2 pi phase.
inline Vec2 phasor(float envelope, float phase) {
  const float angle = kTwoPi * phase;
  return Vec2(envelope * std::cos(angle), envelope * std::sin(angle));
}

Vec2 cell_2d(const Vec2& cell, const Vec2& position, float frequency, float isotropy, float base) {
  Vec2 sum(0.0f);
  for (int i = 0; i < kImpulsesPerCell; ++i) {
    const float word = float(i * 3);
    const Vec2 d = position - hash_float3_to_float2(Vec3(cell, word + 1.0f));
    const float d2 = dot2(d, d);
    if (d2 >= 1.0f) continue;  // (Cycles draws the orientation first; it does not change the test)
    const float random_orientation = (hash_float3_to_float(Vec3(cell, word)) - 0.5f) * kPi;
    const float orientation = base + random_orientation * isotropy;
    const float weight = hash_float3_to_float(Vec3(cell, word + 2.0f)) < 0.5f ? -1.0f : 1.0f;
    const Vec2 f(frequency * std::cos(orientation), frequency * std::sin(orientation));
    sum += weight * phasor(windowed_gaussian(d2), dot2(d, f));
  }
  return sum;
}

// The base direction moved by isotropy * pi * (two hashes) in inclination and azimuth.
Vec3 direction_3d(const Vec3& base, float isotropy, const glm::vec4& seed) {
  if (isotropy == 0.0f) return base;
  float inclination = std::acos(base.z);
  float azimuth = (base.y < 0.0f ? -1.0f : 1.0f) * std::acos(base.x / std::sqrt(base.x * base.x + base.y * base.y));
  const Vec2 random_angles = hash_float4_to_float2(seed) * kPi;
  inclination += random_angles.x * isotropy;
  azimuth += random_angles.y * isotropy;
  const float s = std::sin(inclination);
  return Vec3(s * std::cos(azimuth), s * std::sin(azimuth), std::cos(inclination));
}

Vec2 cell_3d(const Vec3& cell, const Vec3& position, float frequency, float isotropy, const Vec3& base) {
  Vec2 sum(0.0f);
  for (int i = 0; i < kImpulsesPerCell; ++i) {
    const float word = float(i * 3);
    const Vec3 d = position - hash_float4_to_float3(glm::vec4(cell, word + 1.0f));
    const float d2 = dot3(d, d);
    if (d2 >= 1.0f) continue;
    const Vec3 direction = direction_3d(base, isotropy, glm::vec4(cell, word));
    const float weight = hash_float4_to_float(glm::vec4(cell, word + 2.0f)) < 0.5f ? -1.0f : 1.0f;
    sum += weight * phasor(windowed_gaussian(d2), dot3(d, frequency * direction));
  }
  return sum;
}

// Cycles' clamp and max (comparisons: a NaN anisotropy clamps to 0).
inline float clamp_unit(float x) {
  const float lo = x > 0.0f ? x : 0.0f;
  return lo < 1.0f ? lo : 1.0f;
}

}  // namespace

Vec2 gabor_noise_2d(const Vec2& p, float frequency, float isotropy, float orientation) {
  const Vec2 cell = glm::floor(p);
  const Vec2 local = p - cell;
  Vec2 sum(0.0f);
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) {
      const Vec2 offset{float(i), float(j)};
      sum += cell_2d(cell + offset, local - offset, frequency, isotropy, orientation);
    }
  return sum;
}

Vec2 gabor_noise_3d(const Vec3& p, float frequency, float isotropy, const Vec3& orientation) {
  const Vec3 cell = glm::floor(p);
  const Vec3 local = p - cell;
  Vec2 sum(0.0f);
  for (int k = -1; k <= 1; ++k)
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i) {
        const Vec3 offset{float(i), float(j), float(k)};
        sum += cell_3d(cell + offset, local - offset, frequency, isotropy, orientation);
      }
  return sum;
}

GaborOutputs gabor_texture(GaborType type, const GaborInputs& in) {
  const Vec3 p = in.vector * in.scale;
  const float isotropy = 1.0f - clamp_unit(in.anisotropy);
  const float frequency = 0.001f > in.frequency ? 0.001f : in.frequency;
  Vec2 sum;
  float sigma;
  if (type == GaborType::TwoD) {
    sum = gabor_noise_2d(Vec2(p), frequency, isotropy, in.orientation_2d);
    sigma = std::sqrt(float(kImpulsesPerCell) * 0.5f * 0.25f);
  } else {
    const Vec3& o = in.orientation_3d;
    const float length = std::sqrt(dot3(o, o));
    sum = gabor_noise_3d(p, frequency, isotropy, Vec3(o.x / length, o.y / length, o.z / length));
    sigma = std::sqrt(float(kImpulsesPerCell) * 0.5f * (1.0f / (4.0f * 1.41421356237309505f)));
  }
  const float normalization = 6.0f * sigma;
  GaborOutputs out;
  out.value = (sum.y / normalization) * 0.5f + 0.5f;
  out.phase = (std::atan2(sum.y, sum.x) + kPi) / kTwoPi;
  out.intensity = std::sqrt(dot2(sum, sum)) / normalization;
  return out;
}

OpValue gabor_op(const ShaderOpContext& c) {
  GaborInputs in;
  in.vector = c.vector(0);
  in.scale = c.value(1);
  in.frequency = c.value(2);
  in.anisotropy = c.value(3);
  in.orientation_2d = c.value(4);
  in.orientation_3d = c.vector(5);
  const GaborOutputs out = gabor_texture(GaborType(c.ins.mode), in);
  return glm::vec4(out.value, out.phase, out.intensity, 0.0f);
}

}  // namespace torrance::shader
