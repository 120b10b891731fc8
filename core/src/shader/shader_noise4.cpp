// Blender 4.x's Noise Texture as Cycles 4.x computes it: see shader_noise4.h.
#include "torrance/shader/shader_noise4.h"

#include "shader/fractal_sums.h"

#include <cmath>

namespace torrance::shader {

namespace {

inline float lerp(float a, float b, float t) { return a + t * (b - a); }

const auto periodic_noise = [](const auto& p) { return snoise4(p); };

// fBM of the periodic noise: the sums are 3.4's Noise Texture's, with Lacunarity and the raw or
// normalised blend of the fraction.
template <typename P>
float fbm4(const P& p, const fractal::Octaves& o, bool normalize) {
  const fractal::FbmSums s = fractal::fbm_sums(p, o, periodic_noise);
  if (o.fraction != 0.0f) {
    const float more = s.sum + snoise4(s.frequency * p) * s.amplitude;
    return normalize ? lerp(0.5f * s.sum / s.total + 0.5f, 0.5f * more / (s.total + s.amplitude) + 0.5f, o.fraction)
                     : lerp(s.sum, more, o.fraction);
  }
  return normalize ? 0.5f * s.sum / s.total + 0.5f : s.sum;
}

// The types as 3.4's Musgrave Texture sums them (fractal_sums.h), one whole octave more.
template <typename P>
float fractal_at(MusgraveType type, const P& p, float detail, float roughness, float lacunarity, float offset,
                 float gain, bool normalize) {
  return fractal::of_type(type, p, fractal::octaves(detail, 1, roughness, lacunarity), offset, gain, periodic_noise,
                          [&](const P& x, const fractal::Octaves& o) { return fbm4(x, o, normalize); });
}

template <typename P>
NoiseTextureResult texture_at(P p, const Noise4Params& q, float detail, float roughness, bool color) {
  constexpr int n = int(sizeof(P) / sizeof(float));
  p = fractal::distorted(p, q.distortion, periodic_noise);
  const auto at = [&](const P& x) {
    return fractal_at(q.type, x, detail, roughness, q.lacunarity, q.offset, q.gain, q.normalize);
  };
  NoiseTextureResult r;
  r.fac = at(p);
  if (color)
    r.color = Vec3(r.fac, at(p + fractal::seed_offset<P>(float(n))), at(p + fractal::seed_offset<P>(float(n + 1))));
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
  return fbm4(p, fractal::octaves(std::fmin(detail, 15.0f), 1, roughness, 2.0f), true);
}

OpValue noise4_op(const ShaderOpContext& c) {
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
