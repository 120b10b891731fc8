// The hashes behind Blender's procedural textures (Noise, White Noise, Musgrave, Wave, Voronoi),
// bit for bit as Cycles 3.4 computes them: Bob Jenkins' lookup3 applied to one to four 32-bit
// words (https://burtleburtle.net/bob/c/lookup3.c), floats hashed by their bit patterns and
// hashes turned into floats in [0, 1] as float(h) * 2^-32.
//
// Facts worth knowing when matching Cycles:
//   - the state starts at 0xdeadbeef + 4 n + 13 for n words; one to three words go straight into
//     lookup3's final mix, four words take one full mix of the first three and then the final
//     mix with the fourth added to a;
//   - a float is hashed by its bits, so 0.0f and -0.0f hash differently;
//   - the vector-valued hashes hash the key again with an extra word (1, 2) or with its
//     components rotated, in the orders listed at each function below.
//
// The Python twin is python_addon/torrance/shader_graph/hash_ops.py (numpy uint32 arithmetic);
// core/tests/data/shader_noise_cases.json holds hash values both are checked against.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <cstring>

namespace torrance::shader {

namespace hash_detail {

constexpr uint32_t rotl(uint32_t x, int k) { return (x << k) | (x >> (32 - k)); }

// clang-format off
// lookup3's mix(): reversible mixing of three words.
inline void mix(uint32_t& a, uint32_t& b, uint32_t& c) {
  a -= c;  a ^= rotl(c, 4);   c += b;
  b -= a;  b ^= rotl(a, 6);   a += c;
  c -= b;  c ^= rotl(b, 8);   b += a;
  a -= c;  a ^= rotl(c, 16);  c += b;
  b -= a;  b ^= rotl(a, 19);  a += c;
  c -= b;  c ^= rotl(b, 4);   b += a;
}

// lookup3's final(): the last avalanche of three words into c.
inline void final_mix(uint32_t& a, uint32_t& b, uint32_t& c) {
  c ^= b;  c -= rotl(b, 14);
  a ^= c;  a -= rotl(c, 11);
  b ^= a;  b -= rotl(a, 25);
  c ^= b;  c -= rotl(b, 16);
  a ^= c;  a -= rotl(c, 4);
  b ^= a;  b -= rotl(a, 14);
  c ^= b;  c -= rotl(b, 24);
}
// clang-format on

constexpr uint32_t seed(uint32_t words) { return 0xdeadbeefu + (words << 2) + 13u; }

}  // namespace hash_detail

// ---- integers -> uint32 ----

inline uint32_t hash_uint(uint32_t kx) {
  uint32_t a = hash_detail::seed(1), b = a, c = a;
  a += kx;
  hash_detail::final_mix(a, b, c);
  return c;
}

inline uint32_t hash_uint2(uint32_t kx, uint32_t ky) {
  uint32_t a = hash_detail::seed(2), b = a, c = a;
  a += kx;
  b += ky;
  hash_detail::final_mix(a, b, c);
  return c;
}

inline uint32_t hash_uint3(uint32_t kx, uint32_t ky, uint32_t kz) {
  uint32_t a = hash_detail::seed(3), b = a, c = a;
  a += kx;
  b += ky;
  c += kz;
  hash_detail::final_mix(a, b, c);
  return c;
}

inline uint32_t hash_uint4(uint32_t kx, uint32_t ky, uint32_t kz, uint32_t kw) {
  uint32_t a = hash_detail::seed(4), b = a, c = a;
  a += kx;
  b += ky;
  c += kz;
  hash_detail::mix(a, b, c);
  a += kw;
  hash_detail::final_mix(a, b, c);
  return c;
}

// ---- uint32 -> float ----

// [0, 2^32 - 1] -> [0, 1]: float(n) / 2^32 (float(n) rounds, so the top values give exactly 1).
inline float uint_to_float_incl(uint32_t n) { return float(n) * (1.0f / 4294967296.0f); }

// [0, 2^32 - 1] -> [0, 1): float(n) / 4294967808 (one ulp below 1 at most).
inline float uint_to_float_excl(uint32_t n) { return float(n) * (1.0f / 4294967808.0f); }

inline uint32_t float_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

inline float hash_uint_to_float(uint32_t kx) { return uint_to_float_incl(hash_uint(kx)); }
inline float hash_uint2_to_float(uint32_t kx, uint32_t ky) { return uint_to_float_incl(hash_uint2(kx, ky)); }
inline float hash_uint3_to_float(uint32_t kx, uint32_t ky, uint32_t kz) {
  return uint_to_float_incl(hash_uint3(kx, ky, kz));
}
inline float hash_uint4_to_float(uint32_t kx, uint32_t ky, uint32_t kz, uint32_t kw) {
  return uint_to_float_incl(hash_uint4(kx, ky, kz, kw));
}

// ---- floats (by their bits) -> a float in [0, 1] ----

inline float hash_float_to_float(float k) { return hash_uint_to_float(float_bits(k)); }
inline float hash_float2_to_float(const glm::vec2& k) { return hash_uint2_to_float(float_bits(k.x), float_bits(k.y)); }
inline float hash_float3_to_float(const glm::vec3& k) {
  return hash_uint3_to_float(float_bits(k.x), float_bits(k.y), float_bits(k.z));
}
inline float hash_float4_to_float(const glm::vec4& k) {
  return hash_uint4_to_float(float_bits(k.x), float_bits(k.y), float_bits(k.z), float_bits(k.w));
}

// ---- floats -> vectors of floats in [0, 1] ----

// (h(x, y), h(x, y, 1))
inline glm::vec2 hash_float2_to_float2(const glm::vec2& k) {
  return {hash_float2_to_float(k), hash_float3_to_float(glm::vec3(k, 1.0f))};
}

// (h(x, y, z), h(x, y, z, 1), h(x, y, z, 2))
inline glm::vec3 hash_float3_to_float3(const glm::vec3& k) {
  return {hash_float3_to_float(k), hash_float4_to_float(glm::vec4(k, 1.0f)),
          hash_float4_to_float(glm::vec4(k, 2.0f))};
}

// (h(x, y, z, w), h(w, x, y, z), h(z, w, x, y), h(y, z, w, x))
inline glm::vec4 hash_float4_to_float4(const glm::vec4& k) {
  return {hash_float4_to_float(k), hash_float4_to_float(glm::vec4(k.w, k.x, k.y, k.z)),
          hash_float4_to_float(glm::vec4(k.z, k.w, k.x, k.y)),
          hash_float4_to_float(glm::vec4(k.y, k.z, k.w, k.x))};
}

// (h(x), h(x, 1), h(x, 2))
inline glm::vec3 hash_float_to_float3(float k) {
  return {hash_float_to_float(k), hash_float2_to_float(glm::vec2(k, 1.0f)),
          hash_float2_to_float(glm::vec2(k, 2.0f))};
}

// (h(x, y), h(x, y, 1), h(x, y, 2))
inline glm::vec3 hash_float2_to_float3(const glm::vec2& k) {
  return {hash_float2_to_float(k), hash_float3_to_float(glm::vec3(k, 1.0f)),
          hash_float3_to_float(glm::vec3(k, 2.0f))};
}

// (h(x, y, z, w), h(z, x, w, y), h(w, z, y, x))
inline glm::vec3 hash_float4_to_float3(const glm::vec4& k) {
  return {hash_float4_to_float(k), hash_float4_to_float(glm::vec4(k.z, k.x, k.w, k.y)),
          hash_float4_to_float(glm::vec4(k.w, k.z, k.y, k.x))};
}

// Cycles 4.3 added these two for the Gabor Texture (its kernel centres and 3D orientations):
// (h(x, y, z), h(z, x, y))
inline glm::vec2 hash_float3_to_float2(const glm::vec3& k) {
  return {hash_float3_to_float(k), hash_float3_to_float(glm::vec3(k.z, k.x, k.y))};
}

// (h(x, y, z, w), h(z, x, w, y))
inline glm::vec2 hash_float4_to_float2(const glm::vec4& k) {
  return {hash_float4_to_float(k), hash_float4_to_float(glm::vec4(k.z, k.x, k.w, k.y))};
}

// ---- Cycles 5.0+'s integer hashes (the Voronoi Texture's cells in 2D-4D) ----
//
// Jarzynski and Olano's PCG hashes of 2, 3 or 4 words ("Hash Functions for GPU Rendering",
// JCGT 2020) on signed 32-bit integers as Cycles computes them: each word through one LCG step,
// the words stirred into each other, xor-shifted right by 16 (an arithmetic shift: the sign
// bit spreads), stirred again, the sign bit cleared. A result word h becomes float(h) * 2^-31.
// Cycles' integer cell of a float is its truncation, 0x80000000 when it has none (NaN, out of
// int's range), as x86's conversion gives. The Python twin is hash_ops.pcg_hash.

inline uint32_t cell_int(float floored) {
  return floored >= -2147483648.0f && floored < 2147483648.0f ? uint32_t(int32_t(floored)) : 0x80000000u;
}

template <int N>
std::array<uint32_t, N> pcg_hash(std::array<uint32_t, N> v) {
  static_assert(N >= 2 && N <= 4, "PCG hashes 2, 3 or 4 words");
  constexpr uint32_t kMultiplier = 1664525u, kIncrement = 1013904223u;
  const auto stir = [&v] {
    if constexpr (N == 2) {
      v[0] += v[1] * kMultiplier;
      v[1] += v[0] * kMultiplier;
    } else if constexpr (N == 3) {
      v[0] += v[1] * v[2];
      v[1] += v[2] * v[0];
      v[2] += v[0] * v[1];
    } else {
      v[0] += v[1] * v[3];
      v[1] += v[2] * v[0];
      v[2] += v[0] * v[1];
      v[3] += v[1] * v[2];
    }
  };
  for (uint32_t& x : v) x = x * kMultiplier + kIncrement;
  stir();
  for (uint32_t& x : v) x ^= uint32_t(int32_t(x) >> 16);
  stir();
  for (uint32_t& x : v) x &= 0x7FFFFFFFu;
  return v;
}

inline float pcg_to_float(uint32_t h) { return float(int32_t(h)) * (1.0f / 2147483648.0f); }

}  // namespace torrance::shader
