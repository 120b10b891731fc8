// Blender 4.3+'s Gabor Texture node as Cycles computes it (kernel/svm/gabor.h; unchanged from 4.3
// to 5.3 but for how the node's operands are packed): sparse Gabor convolution noise (Lagae et
// al. 2009) with Tavernier et al.'s (2019) fixed impulse count and Bernoulli weights, summed as
// phasors (Tricard et al. 2019) so that the Phase and Intensity come with the Value.
//
// The algorithm, as Cycles runs it in float32:
//   - p = Vector * Scale (2D: its x, y); space is cut into unit cells, and the point sums the
//     impulses of the 3x3 (3x3x3) cells around its own, cells in x-fastest order;
//   - each cell c holds 8 impulses; impulse i's random numbers hash the cell and one more word:
//     3i for its orientation, 3i + 1 for its centre, 3i + 2 for its weight (2D: the float3
//     (c.x, c.y, 3i + k), 3D: the float4 (c.x, c.y, c.z, 3i + k); shader_hash.h's lookup3);
//     the centre is hash_float3_to_float2 / hash_float4_to_float3 of its seed, the weight -1
//     where the hash is below 0.5, else +1;
//   - an impulse whose centre is a unit or more from the point adds nothing; else it adds
//     weight * w(d) * (cos a, sin a), where d is the offset from the centre, w(d) = exp(-pi |d|^2)
//     (0.5 + 0.5 cos(pi |d|^2)) (a Gaussian under a Hann window) and a = 2 pi (d . f), with f the
//     frequency vector: Frequency (at least 0.001) times the impulse's direction;
//   - directions: isotropy = 1 - Anisotropy clamped to [0, 1]. 2D: Orientation 2D + isotropy *
//     pi (h - 0.5), f = Frequency (cos, sin) of it. 3D: the normalised Orientation 3D as is when
//     isotropy is 0; otherwise its inclination acos(z) and azimuth sign(y) acos(x / |(x, y)|)
//     each moved by isotropy * pi * hash_float4_to_float2(seed), turned back into a direction;
//   - the sum (re, im) is normalised by 6 sigma, sigma = sqrt(8 * 0.5 * 0.25) = 1 in 2D and
//     sqrt(8 * 0.5 / (4 sqrt 2)) in 3D: Value = 0.5 im / (6 sigma) + 0.5, Phase =
//     (atan2(im, re) + pi) / (2 pi), Intensity = |(re, im)| / (6 sigma).
//
// Sums run in Cycles' order (impulses within a cell, then cells), the transcendental functions are
// C's float ones; the Python twin (python_addon/torrance/shader_graph/gabor.py) gives the same
// values to an ulp or two of its correctly rounded sin, cos, exp, acos and atan2.
#pragma once

#include "torrance/util/math.h"
#include "torrance/shader/shader_program.h"

#include <cstdint>

namespace torrance::shader {

enum class GaborType : uint8_t { TwoD = 0, ThreeD = 1 };  // Blender's gabor_type '2D', '3D'
constexpr int kGaborModes = 2;

// The summed phasor (re, im) at p; isotropy in [0, 1], frequency > 0, orientation_3d unit.
Vec2 gabor_noise_2d(const Vec2& p, float frequency, float isotropy, float orientation);
Vec2 gabor_noise_3d(const Vec3& p, float frequency, float isotropy, const Vec3& orientation);

struct GaborInputs {
  Vec3 vector{0.0f};
  float scale = 5.0f, frequency = 2.0f, anisotropy = 1.0f;
  float orientation_2d = kPi / 4.0f;
  Vec3 orientation_3d{1.41421356237309505f, 1.41421356237309505f, 0.0f};
};

struct GaborOutputs {
  float value = 0.5f, phase = 0.5f, intensity = 0.0f;
};

GaborOutputs gabor_texture(GaborType type, const GaborInputs& in);

// ---- the op (ShaderOpcode 37) ----
//
// TexGabor  in: Vector, Scale, Frequency, Anisotropy, Orientation 2D (x), Orientation 3D;
//           mode: GaborType; out = (Value, Phase, Intensity, 0): the add-on reads one register
//           for every output of a node (a float in x, a Channel for y and z)
OpValue gabor_op(const ShaderOpContext& c);

}  // namespace torrance::shader
