// Blender's Noise, White Noise, Musgrave and Wave textures as Cycles 3.4 computes them (see
// shader_noise.h). Single precision throughout, in Cycles' order of operations.
#include "torrance/shader/shader_noise.h"

#include "torrance/shader/shader_noise4.h"

#include "shader/fractal_sums.h"
#include "torrance/shader/shader_hash.h"

#include "shader/cpu_dispatch.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace torrance::shader {

namespace {

// ---- Perlin noise's pieces ----

using fractal::float_to_int;

// The lattice cell of x (its floor as an int) and the offset within it.
inline float floor_frac(float x, uint32_t* cell) {
  const float f = std::floor(x);
  *cell = uint32_t(float_to_int(f));
  return x - f;
}

inline float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

// fade of up to four values at once (GCC's vector extension, SSE2 and AVX2 alike): each lane
// the same multiplications and additions in the same order as fade.
typedef float Four __attribute__((vector_size(16)));
inline Four fade4(float x, float y, float z, float w) {
  const Four t = {x, y, z, w};
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

// The gradients choose coordinates and signs by the hash's low bits, which are random: as
// branches they would be mispredicted half the time (most of Perlin noise's cost), so the
// choices are bit operations on the floats' bits: the same floats, chosen without branching.
inline float float_from_bits(uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

// a if condition, else b.
inline float pick(bool condition, float a, float b) {
  const uint32_t mask = 0u - uint32_t(condition);
  return float_from_bits((float_bits(a) & mask) | (float_bits(b) & ~mask));
}

// -v (its sign bit flipped, which is what negation does) if condition is nonzero, else v.
inline float negate_if(float v, uint32_t condition) {
  return float_from_bits(float_bits(v) ^ (uint32_t(condition != 0u) << 31));
}

inline float lerp(float a, float b, float t) { return a + t * (b - a); }

inline float gradient(uint32_t hash, float x) {
  const uint32_t h = hash & 15u;
  return negate_if(float(1u + (h & 7u)), h & 8u) * x;
}

inline float gradient(uint32_t hash, float x, float y) {
  const uint32_t h = hash & 7u;
  const float u = pick(h < 4, x, y);
  const float v = 2.0f * pick(h < 4, y, x);
  return negate_if(u, h & 1u) + negate_if(v, h & 2u);
}

inline float gradient(uint32_t hash, float x, float y, float z) {
  const uint32_t h = hash & 15u;
  const float u = pick(h < 8, x, y);
  const float v = pick(h < 4, y, pick(h == 12 || h == 14, x, z));
  return negate_if(u, h & 1u) + negate_if(v, h & 2u);
}

inline float gradient(uint32_t hash, float x, float y, float z, float w) {
  const uint32_t h = hash & 31u;
  const float u = pick(h < 24, x, y);
  const float v = pick(h < 16, y, z);
  const float s = pick(h < 8, z, w);
  return negate_if(u, h & 1u) + negate_if(v, h & 2u) + negate_if(s, h & 4u);
}

// (1 - y) (v0 (1 - x) + v1 x) + y (v2 (1 - x) + v3 x)
inline float blend2(const float* v, float x, float y) {
  const float x1 = 1.0f - x;
  return (1.0f - y) * (v[0] * x1 + v[1] * x) + y * (v[2] * x1 + v[3] * x);
}

inline float blend3(const float* v, float x, float y, float z) {
  const float x1 = 1.0f - x, y1 = 1.0f - y, z1 = 1.0f - z;
  return z1 * (y1 * (v[0] * x1 + v[1] * x) + y * (v[2] * x1 + v[3] * x)) +
         z * (y1 * (v[4] * x1 + v[5] * x) + y * (v[6] * x1 + v[7] * x));
}

float perlin(float x) {
  uint32_t X;
  const float fx = floor_frac(x, &X);
  return lerp(gradient(hash_uint(X), fx), gradient(hash_uint(X + 1u), fx - 1.0f), fade(fx));
}

// Corner k of a cell: bit 0 the x side (0: X, fx; 1: X + 1, fx - 1), bit 1 y, bit 2 z, bit 3 w.
float perlin(float x, float y) {
  uint32_t X, Y;
  const float fx = floor_frac(x, &X), fy = floor_frac(y, &Y);
  std::array<float, 4> g;
  for (uint32_t k = 0; k < 4; ++k) {
    const uint32_t i = k & 1u, j = (k >> 1) & 1u;
    g[k] = gradient(hash_uint2(X + i, Y + j), fx - float(i), fy - float(j));
  }
  return blend2(g.data(), fade(fx), fade(fy));
}

float perlin(float x, float y, float z) {
  uint32_t X, Y, Z;
  const float fx = floor_frac(x, &X), fy = floor_frac(y, &Y), fz = floor_frac(z, &Z);
  std::array<float, 8> g;
  for (uint32_t k = 0; k < 8; ++k) {
    const uint32_t i = k & 1u, j = (k >> 1) & 1u, l = (k >> 2) & 1u;
    g[k] = gradient(hash_uint3(X + i, Y + j, Z + l), fx - float(i), fy - float(j), fz - float(l));
  }
  const Four t = fade4(fx, fy, fz, 0.0f);
  return blend3(g.data(), t[0], t[1], t[2]);
}

float perlin(float x, float y, float z, float w) {
  uint32_t X, Y, Z, W;
  const float fx = floor_frac(x, &X), fy = floor_frac(y, &Y), fz = floor_frac(z, &Z), fw = floor_frac(w, &W);
  std::array<float, 16> g;
  for (uint32_t k = 0; k < 16; ++k) {
    const uint32_t i = k & 1u, j = (k >> 1) & 1u, l = (k >> 2) & 1u, m = (k >> 3) & 1u;
    g[k] = gradient(hash_uint4(X + i, Y + j, Z + l, W + m), fx - float(i), fy - float(j), fz - float(l),
                    fw - float(m));
  }
  const Four f = fade4(fx, fy, fz, fw);
  return lerp(blend3(g.data(), f[0], f[1], f[2]), blend3(g.data() + 8, f[0], f[1], f[2]), f[3]);
}

inline float finite_or_zero(float v) { return std::isfinite(v) ? v : 0.0f; }

// ---- fractal sums, generic over the point's dimension (fractal_sums.h) ----

const auto signed_noise = [](const auto& p) { return snoise(p); };

template <typename P>
float fbm(const P& p, float detail, float roughness) {
  const float octaves = std::fmin(std::fmax(detail, 0.0f), 15.0f);
  const float gain = std::fmin(std::fmax(roughness, 0.0f), 1.0f);
  const auto unsigned_noise = [](const auto& x) { return unoise(x); };
  const fractal::FbmSums s = fractal::fbm_sums(p, fractal::octaves(octaves, 1, gain, 2.0f), unsigned_noise);
  const float fraction = octaves - std::floor(octaves);
  if (fraction == 0.0f) return s.sum / s.total;
  const float more = (s.sum + unoise(s.frequency * p) * s.amplitude) / (s.total + s.amplitude);
  return (1.0f - fraction) * (s.sum / s.total) + fraction * more;
}

// The Musgrave Texture's fBM (3.4's alone: the point scaled octave by octave, no normalisation).
template <typename P>
float musgrave_fbm(P p, const fractal::Octaves& o) {
  float value = 0.0f, amplitude = 1.0f;
  for (int i = 0; i < o.whole; ++i) {
    value += snoise(p) * amplitude;
    amplitude *= o.step;
    p *= o.lacunarity;
  }
  if (o.fraction != 0.0f) value += o.fraction * snoise(p) * amplitude;
  return value;
}

template <typename P>
float musgrave_at(MusgraveType type, const P& p, float h, float lacunarity, float octaves, float offset, float gain) {
  const fractal::Octaves o = fractal::octaves(octaves, 0, std::pow(lacunarity, -h), lacunarity);
  return fractal::of_type(type, p, o, offset, gain, signed_noise,
                          [](const P& x, const fractal::Octaves& oct) { return musgrave_fbm(x, oct); });
}

// The Noise Texture at a point of N dimensions (float, Vec2, Vec3 or Vec4).
template <typename P>
NoiseTextureResult noise_texture_at(P p, float detail, float roughness, float distortion, bool color) {
  constexpr int n = int(sizeof(P) / sizeof(float));
  const auto offset = [](float seed) { return fractal::seed_offset<P>(seed); };
  p = fractal::distorted(p, distortion, signed_noise);
  NoiseTextureResult r;
  r.fac = fbm(p, detail, roughness);
  if (color)
    r.color = Vec3(r.fac, fbm(p + offset(float(n)), detail, roughness), fbm(p + offset(float(n + 1)), detail, roughness));
  return r;
}

}  // namespace

// ---- Perlin noise ----

float snoise(float p) { return 0.25f * finite_or_zero(perlin(p)); }
float snoise(const Vec2& p) { return 0.6616f * finite_or_zero(perlin(p.x, p.y)); }
float snoise(const Vec3& p) { return 0.9820f * finite_or_zero(perlin(p.x, p.y, p.z)); }
float snoise(const Vec4& p) { return 0.8344f * finite_or_zero(perlin(p.x, p.y, p.z, p.w)); }

// Cycles 4.x's periodic signed noise (shader_noise4.h): each coordinate modulo 100000, plus 0.5
// at |x| >= 1e6; the result kept as it is.
static float periodic(float x) { return std::fmod(x, 100000.0f) + 0.5f * float(std::fabs(x) >= 1000000.0f); }

float snoise4(float p) { return 0.25f * perlin(periodic(p)); }
float snoise4(const Vec2& p) { return 0.6616f * perlin(periodic(p.x), periodic(p.y)); }
float snoise4(const Vec3& p) { return 0.9820f * perlin(periodic(p.x), periodic(p.y), periodic(p.z)); }
float snoise4(const Vec4& p) {
  return 0.8344f * perlin(periodic(p.x), periodic(p.y), periodic(p.z), periodic(p.w));
}

float unoise(float p) { return 0.5f * snoise(p) + 0.5f; }
float unoise(const Vec2& p) { return 0.5f * snoise(p) + 0.5f; }
float unoise(const Vec3& p) { return 0.5f * snoise(p) + 0.5f; }
float unoise(const Vec4& p) { return 0.5f * snoise(p) + 0.5f; }

float fractal_noise(float p, float detail, float roughness) { return fbm(p, detail, roughness); }
float fractal_noise(const Vec2& p, float detail, float roughness) { return fbm(p, detail, roughness); }
float fractal_noise(const Vec3& p, float detail, float roughness) { return fbm(p, detail, roughness); }
float fractal_noise(const Vec4& p, float detail, float roughness) { return fbm(p, detail, roughness); }

// ---- Noise Texture ----

float noise_offset1(float seed) { return 100.0f + hash_float_to_float(seed) * 100.0f; }

Vec4 noise_offset(int dimensions, float seed) {
  Vec4 o(0.0f);
  for (int k = 0; k < dimensions && k < 4; ++k) o[k] = 100.0f + hash_float2_to_float(Vec2(seed, float(k))) * 100.0f;
  return o;
}

NoiseTextureResult noise_texture(int dimensions, const Vec3& vector, float w, float scale, float detail,
                                 float roughness, float distortion, bool color) {
  const Vec3 v = vector * scale;
  const float ws = w * scale;
  switch (dimensions) {
    case 1: return noise_texture_at(ws, detail, roughness, distortion, color);
    case 2: return noise_texture_at(Vec2(v), detail, roughness, distortion, color);
    case 3: return noise_texture_at(v, detail, roughness, distortion, color);
    default: return noise_texture_at(Vec4(v, ws), detail, roughness, distortion, color);
  }
}

// ---- White Noise Texture ----

float white_noise_value(int dimensions, const Vec3& v, float w) {
  switch (dimensions) {
    case 1: return hash_float_to_float(w);
    case 2: return hash_float2_to_float(Vec2(v));
    case 3: return hash_float3_to_float(v);
    default: return hash_float4_to_float(Vec4(v, w));
  }
}

Vec3 white_noise_color(int dimensions, const Vec3& v, float w) {
  switch (dimensions) {
    case 1: return hash_float_to_float3(w);
    case 2: return hash_float2_to_float3(Vec2(v));
    case 3: return hash_float3_to_float3(v);
    default: return hash_float4_to_float3(Vec4(v, w));
  }
}

// ---- Musgrave Texture ----

float musgrave(MusgraveType type, int dimensions, const Vec3& vector, float w, float scale, float detail,
               float dimension, float lacunarity, float offset, float gain) {
  const float h = std::fmax(dimension, 1e-5f);
  const float octaves = std::fmin(std::fmax(detail, 0.0f), 15.0f);
  const float lac = std::fmax(lacunarity, 1e-5f);
  switch (dimensions) {
    case 1: return musgrave_at(type, w * scale, h, lac, octaves, offset, gain);
    case 2: return musgrave_at(type, Vec2(vector) * scale, h, lac, octaves, offset, gain);
    case 3: return musgrave_at(type, vector * scale, h, lac, octaves, offset, gain);
    default: return musgrave_at(type, Vec4(vector, w) * scale, h, lac, octaves, offset, gain);
  }
}

// ---- Wave Texture ----

float wave(WaveType type, int direction, WaveProfile profile, const Vec3& vector, float scale, float distortion,
           float detail, float detail_scale, float detail_roughness, float phase, bool cycles4_noise) {
  const Vec3 p = (vector * scale + 0.000001f) * 0.999999f;
  float n;
  if (type == WaveType::Bands) {
    switch (direction) {
      case 0: n = p.x * 20.0f; break;
      case 1: n = p.y * 20.0f; break;
      case 2: n = p.z * 20.0f; break;
      default: n = (p.x + p.y + p.z) * 10.0f; break;
    }
  } else {
    Vec3 r = p;
    if (direction < 3) r[direction] *= 0.0f;  // the axis' component dropped (as Cycles: times 0)
    n = std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z) * 20.0f;
  }
  n += phase;
  if (distortion != 0.0f) {
    const Vec3 q = p * detail_scale;
    const float noise = cycles4_noise ? wave_fbm4(q, detail, detail_roughness) : fbm(q, detail, detail_roughness);
    n += distortion * (noise * 2.0f - 1.0f);
  }
  constexpr float kHalfPi = 1.57079632679489661923f;
  constexpr float kTwoPiF = 6.28318530717958647692f;
  switch (profile) {
    case WaveProfile::Sine: return 0.5f + 0.5f * std::sin(n - kHalfPi);
    case WaveProfile::Saw: n /= kTwoPiF; return n - std::floor(n);
    default: n /= kTwoPiF; return std::fabs(n - std::floor(n + 0.5f)) * 2.0f;
  }
}

// ---- the ops ----

OpValue noise_op(const ShaderOpContext& c) {
  const bool color = c.ins.flags & 1;
  const NoiseTextureResult r = cpu_dispatch::run_fast([&] {
    return noise_texture(int(c.ins.mode) + 1, c.vector(0), c.value(1), c.value(2), c.value(3), c.value(4),
                         c.value(5), color);
  });
  return color ? glm::vec4(r.color, 1.0f) : glm::vec4(r.fac, 0.0f, 0.0f, 0.0f);
}

OpValue white_noise_op(const ShaderOpContext& c) {
  const int dimensions = int(c.ins.mode) + 1;
  if (c.ins.flags & 1) return glm::vec4(white_noise_color(dimensions, c.vector(0), c.value(1)), 1.0f);
  return glm::vec4(white_noise_value(dimensions, c.vector(0), c.value(1)), 0.0f, 0.0f, 0.0f);
}

OpValue musgrave_op(const ShaderOpContext& c) {
  const float fac = cpu_dispatch::run_fast([&] {
    return musgrave(MusgraveType(c.ins.mode / 4), int(c.ins.mode % 4) + 1, c.vector(0), c.value(1), c.value(2),
                    c.value(3), c.value(4), c.value(5), c.value(6), c.value(7));
  });
  return glm::vec4(fac, 0.0f, 0.0f, 0.0f);
}

OpValue wave_op(const ShaderOpContext& c) {
  const int shape = c.ins.mode / 3;
  const float fac = wave(WaveType(shape / kWaveDirections), shape % kWaveDirections, WaveProfile(c.ins.mode % 3),
                         c.vector(0), c.value(1), c.value(2), c.value(3), c.value(4), c.value(5), c.value(6),
                         (c.ins.flags & 2) != 0);
  return (c.ins.flags & 1) ? glm::vec4(fac, fac, fac, 1.0f) : glm::vec4(fac, 0.0f, 0.0f, 0.0f);
}

}  // namespace torrance::shader
