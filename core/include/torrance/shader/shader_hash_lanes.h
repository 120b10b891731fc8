// shader_hash.h's hashes over arrays of keys: the procedural textures hash many independent keys
// per point (Voronoi's 27 cells in 3D, Perlin noise's 8 corners), and written as plain loops over
// arrays the compiler runs 4 keys (SSE2) or more at once instead of one. Each lane computes
// exactly what the scalar hash computes, so the results are bit for bit shader_hash.h's.
//
// N (the loops' length) is a compile-time count, a multiple of 4 so that no scalar tail is left;
// callers pad their arrays and ignore the extra lanes.
#pragma once

#include "torrance/shader/shader_hash.h"

#include <cstdint>

namespace torrance::shader::lanes {

// float(n) * 2^-32, as uint_to_float_incl: float(n) split as float(n >> 16) * 2^16 + float(n & 0xffff),
// two exact terms whose sum is rounded once, so it is the correctly rounded float(n) that the
// scalar conversion gives, but made of signed conversions, which SSE2 has for vectors (it has
// no unsigned one).
inline float to_unit_float(uint32_t n) {
  const float high = float(int32_t(n >> 16)) * 65536.0f;
  const float low = float(int32_t(n & 0xffffu));
  return (high + low) * (1.0f / 4294967296.0f);
}

template <int N>
void float_bits(const float* in, uint32_t* out) {
  for (int i = 0; i < N; ++i) out[i] = shader::float_bits(in[i]);
}

// out[i] = hash_uint_to_float(x[i]) and the like, for one to four words.
template <int N>
void hash1(const uint32_t* x, float* out) {
  for (int i = 0; i < N; ++i) out[i] = to_unit_float(hash_uint(x[i]));
}
template <int N>
void hash2(const uint32_t* x, const uint32_t* y, float* out) {
  for (int i = 0; i < N; ++i) out[i] = to_unit_float(hash_uint2(x[i], y[i]));
}
template <int N>
void hash3(const uint32_t* x, const uint32_t* y, const uint32_t* z, float* out) {
  for (int i = 0; i < N; ++i) out[i] = to_unit_float(hash_uint3(x[i], y[i], z[i]));
}
template <int N>
void hash4(const uint32_t* x, const uint32_t* y, const uint32_t* z, const uint32_t* w, float* out) {
  for (int i = 0; i < N; ++i) out[i] = to_unit_float(hash_uint4(x[i], y[i], z[i], w[i]));
}

// The same word appended to each key: out[i] = hash of (x[i], w) (two words), (x[i], y[i], w) or
// (x[i], y[i], z[i], w), w a constant (the vector hashes' extra 1.0f and 2.0f).
template <int N>
void hash2_with(const uint32_t* x, uint32_t w, float* out) {
  for (int i = 0; i < N; ++i) out[i] = to_unit_float(hash_uint2(x[i], w));
}
template <int N>
void hash3_with(const uint32_t* x, const uint32_t* y, uint32_t w, float* out) {
  for (int i = 0; i < N; ++i) out[i] = to_unit_float(hash_uint3(x[i], y[i], w));
}
// Two fourth words at once (w1, w2): lookup3 mixes the first three words before it adds the
// fourth, so that mix is shared.
template <int N>
void hash4_with_two(const uint32_t* x, const uint32_t* y, const uint32_t* z, uint32_t w1, uint32_t w2, float* out1,
                    float* out2) {
  for (int i = 0; i < N; ++i) {
    uint32_t a = hash_detail::seed(4) + x[i], b = hash_detail::seed(4) + y[i], c = hash_detail::seed(4) + z[i];
    hash_detail::mix(a, b, c);
    uint32_t a1 = a + w1, b1 = b, c1 = c;
    hash_detail::final_mix(a1, b1, c1);
    uint32_t a2 = a + w2, b2 = b, c2 = c;
    hash_detail::final_mix(a2, b2, c2);
    out1[i] = to_unit_float(c1);
    out2[i] = to_unit_float(c2);
  }
}

}  // namespace torrance::shader::lanes
