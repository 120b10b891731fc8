// The fractal sums of Blender's noise textures, one loop per fractal type, shared by Cycles 3.4's
// textures (shader_noise.cpp: the Noise Texture's fBM, the Musgrave Texture) and Cycles 4.x's
// (shader_noise4.cpp: the Noise Texture's five types). Generic over the point's dimension (float,
// Vec2, Vec3, Vec4) and over what the versions change:
//   - `noise`, the signed (or 3.4's Noise Texture: unsigned) noise of one octave at a point;
//   - Octaves: how many whole octaves are summed, the fraction of one more blended in, each
//     octave's amplitude over the last one's (3.4's Musgrave: lacunarity^-dimension; the Noise
//     Textures: Roughness) and its frequency over the last one's (Lacunarity; 3.4's Noise: 2).
// 4.x sums one whole octave more than 3.4's Musgrave for the same Detail (whole = its int + 1).
// Also the Noise Texture's distortion and colour offsets, which both versions share.
// Single precision in Cycles' order of operations: every texture's results are bit for bit its
// own formulas' (the Python twin: python_addon/torrance/shader_graph/fractals.py).
#pragma once

#include "torrance/shader/shader_noise.h"

#include <cmath>
#include <cstdint>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace torrance::shader::fractal {

// x86's float -> int32 truncation: values outside int32 (and NaN) give INT_MIN, as Cycles' kernel
// gets from cvttss2si (C leaves the conversion undefined there).
inline int32_t float_to_int(float f) {
#if defined(__SSE__)
  return _mm_cvtt_ss2si(_mm_set_ss(f));  // that instruction itself: no range test and branch
#else
  if (f >= -2147483648.0f && f < 2147483648.0f) return int32_t(f);
  return INT32_MIN;
#endif
}

struct Octaves {
  int32_t whole;     // octaves summed in full
  float fraction;    // of one more octave (0: none)
  float step;        // an octave's amplitude over the previous one's
  float lacunarity;  // an octave's frequency over the previous one's
};

// Octaves of a Detail (clamped by the caller) summing its int and `extra` more whole octaves.
inline Octaves octaves(float detail, int32_t extra, float step, float lacunarity) {
  const int32_t n = float_to_int(detail);
  return Octaves{n == INT32_MIN ? n : n + extra, detail - std::floor(detail), step, lacunarity};
}

// fBM's running sums over the whole octaves: sum of noise(frequency p) amplitude, the amplitudes'
// total, and the next octave's amplitude and frequency (for the fraction, which each version
// blends its own way).
struct FbmSums {
  float sum = 0.0f, total = 0.0f, amplitude = 1.0f, frequency = 1.0f;
};

template <typename P, typename Noise>
FbmSums fbm_sums(const P& p, const Octaves& o, Noise noise) {
  FbmSums s;
  for (int32_t i = 0; i < o.whole; ++i) {
    s.sum += noise(s.frequency * p) * s.amplitude;
    s.total += s.amplitude;
    s.amplitude *= o.step;
    s.frequency *= o.lacunarity;
  }
  return s;
}

template <typename P, typename Noise>
float multifractal(P p, const Octaves& o, Noise noise) {
  float value = 1.0f, amplitude = 1.0f;
  for (int32_t i = 0; i < o.whole; ++i) {
    value *= amplitude * noise(p) + 1.0f;
    amplitude *= o.step;
    p *= o.lacunarity;
  }
  if (o.fraction != 0.0f) value *= o.fraction * amplitude * noise(p) + 1.0f;
  return value;
}

template <typename P, typename Noise>
float hetero_terrain(P p, const Octaves& o, float offset, Noise noise) {
  float amplitude = o.step;
  float value = offset + noise(p);
  p *= o.lacunarity;
  for (int32_t i = 1; i < o.whole; ++i) {
    value += (noise(p) + offset) * amplitude * value;
    amplitude *= o.step;
    p *= o.lacunarity;
  }
  if (o.fraction != 0.0f) value += o.fraction * ((noise(p) + offset) * amplitude * value);
  return value;
}

template <typename P, typename Noise>
float hybrid_multifractal(P p, const Octaves& o, float offset, float gain, Noise noise) {
  float amplitude = 1.0f, value = 0.0f, weight = 1.0f;
  for (int32_t i = 0; weight > 0.001f && i < o.whole; ++i) {
    if (weight > 1.0f) weight = 1.0f;
    const float signal = (noise(p) + offset) * amplitude;
    amplitude *= o.step;
    value += weight * signal;
    weight *= gain * signal;
    p *= o.lacunarity;
  }
  if (o.fraction != 0.0f && weight > 0.001f) {
    if (weight > 1.0f) weight = 1.0f;
    value += o.fraction * weight * ((noise(p) + offset) * amplitude);
  }
  return value;
}

template <typename P, typename Noise>
float ridged_multifractal(P p, const Octaves& o, float offset, float gain, Noise noise) {
  float amplitude = o.step;
  float signal = offset - std::fabs(noise(p));
  signal *= signal;
  float value = signal;
  for (int32_t i = 1; i < o.whole; ++i) {
    p *= o.lacunarity;
    const float weight = std::fmin(std::fmax(signal * gain, 0.0f), 1.0f);
    signal = offset - std::fabs(noise(p));
    signal *= signal;
    signal *= weight;
    value += signal * amplitude;
    amplitude *= o.step;
  }
  return value;
}

// The fractal of `type` at p; fbm(p, o): the version's own fBM.
template <typename P, typename Noise, typename Fbm>
float of_type(MusgraveType type, const P& p, const Octaves& o, float offset, float gain, Noise noise, Fbm fbm) {
  switch (type) {
    case MusgraveType::Multifractal: return multifractal(p, o, noise);
    case MusgraveType::RidgedMultifractal: return ridged_multifractal(p, o, offset, gain, noise);
    case MusgraveType::HybridMultifractal: return hybrid_multifractal(p, o, offset, gain, noise);
    case MusgraveType::FBM: return fbm(p, o);
    case MusgraveType::HeteroTerrain: return hetero_terrain(p, o, offset, noise);
  }
  return 0.0f;
}

// ---- the Noise Texture's point, in both versions ----

// The offset of seed `seed` added to a point of P's dimension (Cycles' random_float<N>_offset).
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

// p moved by Distortion: along each axis k by noise(p + seed_offset(k)) * distortion.
template <typename P, typename Noise>
P distorted(P p, float distortion, Noise noise) {
  constexpr int n = int(sizeof(P) / sizeof(float));
  if (distortion == 0.0f) return p;
  if constexpr (n == 1) {
    p += noise(p + seed_offset<P>(0.0f)) * distortion;
  } else {
    P shift;
    for (int k = 0; k < n; ++k) shift[k] = noise(p + seed_offset<P>(float(k))) * distortion;
    p += shift;
  }
  return p;
}

}  // namespace torrance::shader::fractal
