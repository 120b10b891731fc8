// Blender 4.x's Noise Texture as Cycles 4.x computes it (kernel/svm/noisetex.h, fractal_noise.h,
// noise.h of Cycles 4.2), beside 3.4's (shader_noise.h), whose Perlin noise and hash it shares.
// The add-on's reader picks this op for a Noise node that has 4.0's Normalize setting.
//
// What Cycles 4.x changed:
//   - signed noise is periodic: each coordinate is first taken modulo 100000 (C's fmod, exact),
//     plus 0.5 where |x| >= 1e6 (off the lattice); a non-finite result is kept (3.4: 0);
//   - the Noise Texture has Blender 4.1's five noise types, which were the Musgrave Texture's
//     (MusgraveType's order and names), with Lacunarity (the frequency step; 3.4: 2), Roughness
//     as the amplitude step (Musgrave's lacunarity^-dimension), floor(detail) + 1 octaves (the
//     Musgrave's floor(detail)), detail clamped to [0, 15] and roughness to >= 0 (no upper clamp);
//   - fBM sums signed noise; Normalize (the 4.0 default) gives 0.5 sum / (sum of amplitudes) + 0.5,
//     without it the raw sum; a fractional detail blends one more octave in (the two normalised
//     separately when normalising);
//   - the other types as Musgrave's formulas with one octave more (hybrid's weight test and cap,
//     ridged's squared offset - |noise| weighted by the last octave's signal x gain; hetero
//     terrain's octaves scaled by the value so far), never normalised.
// Distortion, the colour's offsets and the point's scaling are 3.4's, and so are the fractal
// loops (core/src/shader/fractal_sums.h: 3.4's with one whole octave more, Roughness as the step).
//
// The Wave Texture's distortion in Cycles 4.x is this fBM (lacunarity 2, normalised) of the
// periodic noise: wave_fbm4 (the Wave op's flags & 2). Its detail is capped at 15 here (Cycles 4.x
// leaves it unclamped: a detail far beyond the node's range loops that many octaves).
//
// Results are bit for bit those of the Python twin (python_addon/torrance/shader_graph/noise4.py).
#pragma once

#include "torrance/shader/shader_noise.h"

namespace torrance::shader {

// Cycles 4.x's signed noise (periodic, see above).
float snoise4(float p);
float snoise4(const Vec2& p);
float snoise4(const Vec3& p);
float snoise4(const Vec4& p);

// The noise of `type` (MusgraveType's order: Blender 4.1's noise_type) at p, detail and
// roughness as given (the texture clamps them), lacunarity, offset, gain; normalize: fBM's.
float fractal_noise4(MusgraveType type, float p, float detail, float roughness, float lacunarity, float offset,
                     float gain, bool normalize);
float fractal_noise4(MusgraveType type, const Vec2& p, float detail, float roughness, float lacunarity,
                     float offset, float gain, bool normalize);
float fractal_noise4(MusgraveType type, const Vec3& p, float detail, float roughness, float lacunarity,
                     float offset, float gain, bool normalize);
float fractal_noise4(MusgraveType type, const Vec4& p, float detail, float roughness, float lacunarity,
                     float offset, float gain, bool normalize);

struct Noise4Params {
  MusgraveType type = MusgraveType::FBM;
  int dimensions = 3;
  float scale = 5.0f, detail = 2.0f, roughness = 0.5f, lacunarity = 2.0f, offset = 0.0f, gain = 1.0f;
  float distortion = 0.0f;
  bool normalize = true;
};

// The Noise Texture of Blender 4.x at vector and w (used as 3.4's noise_texture uses them).
NoiseTextureResult noise_texture4(const Noise4Params& params, const Vec3& vector, float w, bool color);

// The Wave Texture's distortion noise in Cycles 4.x: normalised fBM, lacunarity 2.
float wave_fbm4(const Vec3& p, float detail, float roughness);

// ---- the op (ShaderOpcode 36) ----
//
// NoiseV4  in: vector, w, scale, detail, roughness, lacunarity, offset, gain, distortion;
//          mode = type * 4 + dimensions - 1 (20 modes); flags & 1: Color (fac, g, b, 1), else
//          Fac (fac, 0, 0, 0); flags & 2: normalize
constexpr int kNoise4Modes = kMusgraveTypes * 4;

OpValue noise4_op(const ShaderOpContext& c);

}  // namespace torrance::shader
