// Blender 4.x's Noise Texture as Cycles 4.x computes it: see shader_noise4.h.
#include "torrance/shader_noise4.h"

#include <cmath>
#include <cstdint>

namespace torrance::shader {

namespace {

// x86's float -> int conversion as Cycles' float_to_int (outside int32 and NaN: INT_MIN).
inline int32_t octave_count(float detail) {
  if (detail >= -2147483648.0f && detail < 2147483648.0f) return int32_t(detail);
  return INT32_MIN;
}

inline float lerp(float a, float b, float t) { return a + t * (b - a); }

template <typename P>
float fbm4(P p, float detail, float roughness, float lacunarity, bool normalize) {
  float frequency = 1.0f, amplitude = 1.0f, total = 0.0f, sum = 0.0f;
  const int n = octave_count(detail);
  for (int i = 0; i <= n; ++i) {
    sum += snoise4(frequency * p) * amplitude;
    total += amplitude;
    amplitude *= roughness;
    frequency *= lacunarity;
  }
  const float fraction = detail - std::floor(detail);
  if (fraction != 0.0f) {
    const float more = sum + snoise4(frequency * p) * amplitude;
    return normalize ? lerp(0.5f * sum / total + 0.5f, 0.5f * more / (total + amplitude) + 0.5f, fraction)
                     : lerp(sum, more, fraction);
  }
  return normalize ? 0.5f * sum / total + 0.5f : sum;
}

template <typename P>
float multifractal4(P p, float detail, float roughness, float lacunarity) {
  float value = 1.0f, amplitude = 1.0f;
  const int n = octave_count(detail);
  for (int i = 0; i <= n; ++i) {
    value *= amplitude * snoise4(p) + 1.0f;
    amplitude *= roughness;
    p *= lacunarity;
  }
  const float fraction = detail - std::floor(detail);
  if (fraction != 0.0f) value *= fraction * amplitude * snoise4(p) + 1.0f;
  return value;
}

template <typename P>
float hetero_terrain4(P p, float detail, float roughness, float lacunarity, float offset) {
  float amplitude = roughness;
  float value = offset + snoise4(p);
  p *= lacunarity;
  const int n = octave_count(detail);
  for (int i = 1; i <= n; ++i) {
    value += (snoise4(p) + offset) * amplitude * value;
    amplitude *= roughness;
    p *= lacunarity;
  }
  const float fraction = detail - std::floor(detail);
  if (fraction != 0.0f) value += fraction * ((snoise4(p) + offset) * amplitude * value);
  return value;
}

template <typename P>
float hybrid_multifractal4(P p, float detail, float roughness, float lacunarity, float offset, float gain) {
  float amplitude = 1.0f, value = 0.0f, weight = 1.0f;
  const int n = octave_count(detail);
  for (int i = 0; weight > 0.001f && i <= n; ++i) {
    if (weight > 1.0f) weight = 1.0f;
    const float signal = (snoise4(p) + offset) * amplitude;
    amplitude *= roughness;
    value += weight * signal;
    weight *= gain * signal;
    p *= lacunarity;
  }
  const float fraction = detail - std::floor(detail);
  if (fraction != 0.0f && weight > 0.001f) {
    if (weight > 1.0f) weight = 1.0f;
    value += fraction * weight * ((snoise4(p) + offset) * amplitude);
  }
  return value;
}

template <typename P>
float ridged_multifractal4(P p, float detail, float roughness, float lacunarity, float offset, float gain) {
  float amplitude = roughness;
  float signal = offset - std::fabs(snoise4(p));
  signal *= signal;
  float value = signal;
  const int n = octave_count(detail);
  for (int i = 1; i <= n; ++i) {
    p *= lacunarity;
    const float weight = std::fmin(std::fmax(signal * gain, 0.0f), 1.0f);
    signal = offset - std::fabs(snoise4(p));
    signal *= signal;
    signal *= weight;
    value += signal * amplitude;
    amplitude *= roughness;
  }
  return value;
}

template <typename P>
float fractal_at(MusgraveType type, const P& p, float detail, float roughness, float lacunarity, float offset,
                 float gain, bool normalize) {
  switch (type) {
    case MusgraveType::Multifractal: return multifractal4(p, detail, roughness, lacunarity);
    case MusgraveType::RidgedMultifractal: return ridged_multifractal4(p, detail, roughness, lacunarity, offset, gain);
    case MusgraveType::HybridMultifractal: return hybrid_multifractal4(p, detail, roughness, lacunarity, offset, gain);
    case MusgraveType::FBM: return fbm4(p, detail, roughness, lacunarity, normalize);
    case MusgraveType::HeteroTerrain: return hetero_terrain4(p, detail, roughness, lacunarity, offset);
  }
  return 0.0f;
}

template <typename P>
P seed_offset(float seed) {
  constexpr int n = int(sizeof(P) / sizeof(float));
  if constexpr (n == 1) {
    return noise_offset1(seed);
  } else {
    const Vec4 o = noise_offset(n, seed);
    P out;
    for (int k = 0; k < n; ++k) out[k] = o[k];
    return out;
  }
}

template <typename P>
NoiseTextureResult texture_at(P p, const Noise4Params& q, float detail, float roughness, bool color) {
  constexpr int n = int(sizeof(P) / sizeof(float));
  if (q.distortion != 0.0f) {
    if constexpr (n == 1) {
      p += snoise4(p + seed_offset<P>(0.0f)) * q.distortion;
    } else {
      P shift;
      for (int k = 0; k < n; ++k) shift[k] = snoise4(p + seed_offset<P>(float(k))) * q.distortion;
      p += shift;
    }
  }
  const auto at = [&](const P& x) {
    return fractal_at(q.type, x, detail, roughness, q.lacunarity, q.offset, q.gain, q.normalize);
  };
  NoiseTextureResult r;
  r.fac = at(p);
  if (color) r.color = Vec3(r.fac, at(p + seed_offset<P>(float(n))), at(p + seed_offset<P>(float(n + 1))));
  return r;
}

}  // namespace

float fractal_noise4(MusgraveType type, float p, float detail, float roughness, float lacunarity, float offset,
                     float gain, bool normalize) {
  return fractal_at(type, p, detail, roughness, lacunarity, offset, gain, normalize);
}
float fractal_noise4(MusgraveType type, const Vec2& p, float detail, float roughness, float lacunarity,
                     float offset, float gain, bool normalize) {
  return fractal_at(type, p, detail, roughness, lacunarity, offset, gain, normalize);
}
float fractal_noise4(MusgraveType type, const Vec3& p, float detail, float roughness, float lacunarity,
                     float offset, float gain, bool normalize) {
  return fractal_at(type, p, detail, roughness, lacunarity, offset, gain, normalize);
}
float fractal_noise4(MusgraveType type, const Vec4& p, float detail, float roughness, float lacunarity,
                     float offset, float gain, bool normalize) {
  return fractal_at(type, p, detail, roughness, lacunarity, offset, gain, normalize);
}

NoiseTextureResult noise_texture4(const Noise4Params& q, const Vec3& vector, float w, bool color) {
  const float detail = std::fmin(std::fmax(q.detail, 0.0f), 15.0f);
  const float roughness = std::fmax(q.roughness, 0.0f);
  const Vec3 v = vector * q.scale;
  const float ws = w * q.scale;
  switch (q.dimensions) {
    case 1: return texture_at(ws, q, detail, roughness, color);
    case 2: return texture_at(Vec2(v), q, detail, roughness, color);
    case 3: return texture_at(v, q, detail, roughness, color);
    default: return texture_at(Vec4(v, ws), q, detail, roughness, color);
  }
}

float wave_fbm4(const Vec3& p, float detail, float roughness) {
  return fbm4(p, std::fmin(detail, 15.0f), roughness, 2.0f, true);
}

glm::vec4 noise4_op(const ShaderOpContext& c) {
  Noise4Params q;
  q.type = MusgraveType(c.ins.mode / 4);
  q.dimensions = int(c.ins.mode % 4) + 1;
  q.scale = c.value(2);
  q.detail = c.value(3);
  q.roughness = c.value(4);
  q.lacunarity = c.value(5);
  q.offset = c.value(6);
  q.gain = c.value(7);
  q.distortion = c.value(8);
  q.normalize = (c.ins.flags & 2) != 0;
  const bool color = c.ins.flags & 1;
  const NoiseTextureResult r = noise_texture4(q, c.vector(0), c.value(1), color);
  return color ? glm::vec4(r.color, 1.0f) : glm::vec4(r.fac, 0.0f, 0.0f, 0.0f);
}

}  // namespace torrance::shader
