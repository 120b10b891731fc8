// Blender's noise textures as Cycles 3.4 computes them (kernel/svm/noise.h, fractal_noise.h,
// noisetex.h, white_noise.h, musgrave.h, wave.h): the same hash (shader_hash.h), the same Perlin
// noise and the same fractal sums (one loop per fractal type, shared with Cycles 4.x's Noise
// Texture: core/src/shader/fractal_sums.h), so the patterns are Cycles' own, not look-alikes.
//
// Perlin noise (1D to 4D) as Cycles has it:
//   - the lattice cell of x is floor(x), converted to int as x86 does (a value outside int32,
//     inf or NaN becomes INT_MIN); its corners are hashed with hash_uint<N> of the integer
//     coordinates (as uint32: negative cells wrap);
//   - each corner's gradient is a function of its hash's low bits: 1D g = 1 + (h & 7), negated
//     if h & 8, times x; 2D (h & 7) picks (x, 2y) or (y, 2x) and the signs; 3D (h & 15) picks two
//     of the offsets as in Perlin's improved noise (12 edges, 12 and 14 repeat x); 4D (h & 31)
//     three of the four (32 edges);
//   - the corners blend with Perlin's quintic fade 6t^5 - 15t^4 + 10t^3, nested x, then y, ...
//     (1D and 4D's last axis: a + t (b - a); the others (1 - t) a + t b);
//   - signed noise (snoise) scales the result to about [-1, 1] by 0.25, 0.6616, 0.982 and 0.8344
//     (1D to 4D) after setting a non-finite one to 0; unsigned noise is 0.5 snoise + 0.5.
// Cycles' CPU kernels evaluate 2D to 4D noise with SSE/AVX (the same formulas, the blends
// reassociated, fused multiply-adds on AVX2): they agree with the scalar order kept here (the
// GPU kernels' order) to a few ulps.
//
// The expressions keep Cycles' order of operations in single precision; compiled without
// floating-point contraction (the default on x86-64 without -march), results are bit for bit
// those of the Python twin (python_addon/torrance/shader_graph/noise.py). Both are checked
// against the same table, core/tests/data/shader_noise_cases.json, whose values Blender 3.4.1's
// Cycles renders too.
#pragma once

#include "torrance/util/math.h"
#include "torrance/shader/shader_program.h"

#include <cstdint>

namespace torrance::shader {

using Vec4 = glm::vec4;

// ---- Perlin noise ----

// Signed Perlin noise, about [-1, 1] (0 at every lattice point).
float snoise(float p);
float snoise(const Vec2& p);
float snoise(const Vec3& p);
float snoise(const Vec4& p);

// Unsigned: 0.5 snoise + 0.5, about [0, 1].
float unoise(float p);
float unoise(const Vec2& p);
float unoise(const Vec3& p);
float unoise(const Vec4& p);

// Fractal (fBm) noise as the Noise and Wave textures sum it: octaves = detail clamped to [0, 15];
// floor(octaves) + 1 octaves of unoise at frequencies 1, 2, 4, ..., amplitudes roughness^i
// (roughness clamped to [0, 1]), normalised by the sum of the amplitudes; a fractional part of
// the octaves blends in one more octave (each sum normalised by its own amplitudes).
float fractal_noise(float p, float detail, float roughness);
float fractal_noise(const Vec2& p, float detail, float roughness);
float fractal_noise(const Vec3& p, float detail, float roughness);
float fractal_noise(const Vec4& p, float detail, float roughness);

// ---- Noise Texture ----

struct NoiseTextureResult {
  float fac = 0.0f;
  Vec3 color{0.0f};  // (fac, fBm at p + offset, fBm at p + another offset); 0 unless asked for
};

// The Noise Texture of `dimensions` (1 to 4) at vector (xyz) and w, both scaled by `scale`:
// 1D reads w, 2D the vector's xy, 3D the vector, 4D (vector, w). A nonzero distortion first moves
// the point by distortion * snoise per axis, each at the point plus a fixed offset in
// [100, 200]^N (seeds 0 .. N-1); Fac is fractal_noise at the moved point; Color's green and blue
// are fractal_noise at the moved point plus the offsets of the next two seeds (N, N + 1).
NoiseTextureResult noise_texture(int dimensions, const Vec3& vector, float w, float scale, float detail,
                                 float roughness, float distortion, bool color);

// The offset of seed `seed` (Cycles' random_float<N>_offset): 1D 100 + 100 hash(seed); ND its
// component k is 100 + 100 hash(seed, k).
float noise_offset1(float seed);
Vec4 noise_offset(int dimensions, float seed);  // the first `dimensions` components

// ---- White Noise Texture ----

// The hash of the point's bits: 1D w, 2D (x, y), 3D (x, y, z), 4D (x, y, z, w); Value in [0, 1]
// and Color (hash_float*_to_float3).
float white_noise_value(int dimensions, const Vec3& vector, float w);
Vec3 white_noise_color(int dimensions, const Vec3& vector, float w);

// ---- Musgrave Texture ----

// Blender's musgrave_type identifiers in the order of its menu.
enum class MusgraveType : uint8_t {
  Multifractal,        // MULTIFRACTAL: product of (1 + amplitude snoise)
  RidgedMultifractal,  // RIDGED_MULTIFRACTAL: (offset - |snoise|)^2 weighted by the last octave x gain
  HybridMultifractal,  // HYBRID_MULTIFRACTAL: sums weighted by the previous octaves' product x gain
  FBM,                 // FBM: sum of amplitude snoise
  HeteroTerrain,       // HETERO_TERRAIN: each octave scaled by the value so far
};
constexpr int kMusgraveTypes = 5;

// The Musgrave Texture: the point as the Noise Texture's (dimensions 1 to 4) times scale;
// dimension (H) at least 1e-5, detail (octaves) clamped to [0, 15], lacunarity at least 1e-5;
// octave i has frequency lacunarity^i and amplitude lacunarity^(-H i). Unlike the Noise
// Texture's fBm: floor(octaves) octaves (not + 1), signed noise, no normalisation; a fractional
// part of the octaves adds that fraction of the next octave (Ridged ignores it; Hybrid only while
// its weight is above 0.001, the weight capped at 1).
float musgrave(MusgraveType type, int dimensions, const Vec3& vector, float w, float scale, float detail,
               float dimension, float lacunarity, float offset, float gain);

// ---- Wave Texture ----

enum class WaveType : uint8_t { Bands, Rings };
// Bands: X, Y, Z, Diagonal; rings: X, Y, Z (rings around that axis), Spherical.
constexpr int kWaveDirections = 4;
enum class WaveProfile : uint8_t { Sine, Saw, Triangle };

// The Wave Texture at p = vector * scale: p is nudged to (p + 1e-6) * 0.999999; bands take
// n = 20 p's coordinate (diagonal: 10 (x + y + z)), rings 20 |p| with the axis' component
// dropped (spherical: all kept); n += phase, and with a nonzero distortion n += distortion
// (2 fractal_noise(p detail_scale, detail, detail_roughness) - 1). Sine: 0.5 + 0.5 sin(n - pi/2);
// Saw: fract(n / 2pi); Triangle: 2 |n / 2pi - floor(n / 2pi + 0.5)|.
// cycles4_noise: the distortion is Cycles 4.x's fBM (shader_noise4.h's wave_fbm4).
float wave(WaveType type, int direction, WaveProfile profile, const Vec3& vector, float scale, float distortion,
           float detail, float detail_scale, float detail_roughness, float phase, bool cycles4_noise = false);

// ---- the ops (ShaderOpcode 32-35; 36, Blender 4.x's Noise Texture: shader_noise4.h) ----
//
// Noise       in: vector, w, scale, detail, roughness, distortion; mode = dimensions - 1;
//             flags & 1: Color (fac, g, b, 1) (Fac is its x), else Fac (fac, 0, 0, 0)
// WhiteNoise  in: vector, w; mode = dimensions - 1; flags & 1: Color (r, g, b, 1) (Value is
//             its x, as hash_float*_to_float3 starts with the key's hash), else Value
//             (value, 0, 0, 0)
// Musgrave    in: vector, w, scale, detail, dimension, lacunarity, offset, gain;
//             mode = type * 4 + dimensions - 1 (20 modes); out (fac, 0, 0, 0)
// Wave        in: vector, scale, distortion, detail, detail scale, detail roughness, phase;
//             mode = (type * 4 + direction) * 3 + profile (24 modes); flags & 1: Color
//             (fac, fac, fac, 1), else Fac (fac, 0, 0, 0); flags & 2: Cycles 4.x's distortion
constexpr int kNoiseModes = 4;
constexpr int kWhiteNoiseModes = 4;
constexpr int kMusgraveModes = kMusgraveTypes * 4;
constexpr int kWaveModes = 2 * kWaveDirections * 3;

OpValue noise_op(const ShaderOpContext& c);
OpValue white_noise_op(const ShaderOpContext& c);
OpValue musgrave_op(const ShaderOpContext& c);
OpValue wave_op(const ShaderOpContext& c);

}  // namespace torrance::shader
