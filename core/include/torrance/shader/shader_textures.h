// The shader graph's texture family (opcodes 56-71): Blender's Checker, Gradient, Brick and Magic
// Texture nodes as Cycles 3.4 evaluates them on the CPU, in float32 and in Cycles' order of
// operations (the Python twin, python_addon/torrance/shader_graph/textures.py, is the add-on's
// constant folder; both are checked against core/tests/data/shader_textures_cases.json, whose
// values Blender 3.4.1's Cycles rendered).
//
// Each op writes one of its node's two outputs: flags & 1 clear, the Color (r, g, b, 1); set, the
// Fac (fac, 0, 0, 0). The add-on emits one instruction per output used. A node's unlinked Vector
// is Cycles' Generated coordinates (the add-on links them); the node's hidden texture mapping must
// be the identity (the add-on checks). The ops and what they read:
//   TexChecker (56)   in0 Vector, in1 Color1, in2 Color2, in3.x Scale
//   TexGradient (57)  in0 Vector; mode: GradientType
//   TexBrick (58)     in0 Vector, in1 Color1, in2 Color2, in3 Mortar, in4.x Scale, in5.x Mortar
//                     Size, in6.x Mortar Smooth, in7.x Bias, in8.x Brick Width, in9.x Row Height,
//                     in10 the node's settings (Offset, Offset Frequency, Squash, Squash Frequency)
//   TexMagic (59)     in0 Vector, in1.x Scale, in2.x Distortion; mode: Depth (0-10)
//
// Cycles converts floats to ints as x86 does (truncation; NaN and values beyond int's range give
// INT_MIN); so do these functions, which keeps them defined for any input.
#pragma once

#include "torrance/util/math.h"
#include "torrance/shader/shader_program.h"

#include <cstdint>

namespace torrance::shader {

// ---- Checker -------------------------------------------------------------------------------------
// Cycles' checker at p = Vector * Scale: 1 on Color1's squares, 0 on Color2's. Each coordinate is
// nudged ((x + 1e-6) * 0.999999) before it is floored, so that unit-aligned inputs do not
// flicker; a cell is Color1's when (x's parity equals y's) equals (z's parity is odd).
float checker(const Vec3& p);

// ---- Gradient ------------------------------------------------------------------------------------
// The Gradient node's types, in Blender's order of identifiers (the add-on's GRADIENT_TYPES).
enum class GradientType : uint8_t {
  Linear,           // x
  Quadratic,        // max(x, 0)^2
  Easing,           // smoothstep of x clamped to [0, 1]: 3 t^2 - 2 t^3
  Diagonal,         // (x + y) / 2
  Spherical,        // r = max(0.999999 - |p|, 0)
  QuadraticSphere,  // r^2 (r as Spherical's)
  Radial,           // atan2(y, x) / 2 pi + 0.5
};
constexpr int kGradientTypeCount = int(GradientType::Radial) + 1;

// The Gradient node's Fac (its Color is the Fac in r, g and b): the type's value clamped to [0, 1]
// (NaN -> 0). A type outside the enumeration gives 0.
float gradient(GradientType type, const Vec3& p);

// ---- Brick ---------------------------------------------------------------------------------------
// The Brick node's settings (node properties, not sockets). Every offset_frequency-th row (rows 0,
// +-f, +-2f, ...) is shifted by offset times its brick width; every squash_frequency-th row's
// bricks are squash times as wide. Blender keeps both frequencies in 1..99; either <= 0 turns both
// offset and squash off.
struct BrickRows {
  float offset = 0.5f;
  int offset_frequency = 2;
  float squash = 1.0f;
  int squash_frequency = 2;
};

// Cycles' integer noise for a brick's tint: n -> [0, 1), a hash in wrapping 32-bit arithmetic.
float brick_noise(uint32_t n);

struct BrickSample {
  float tint = 0.0f;    // the brick's blend from Color1 to Color2: noise + Bias, clamped to [0, 1]
  float mortar = 0.0f;  // 1 in the mortar, 0 on the brick, a smoothstep between (the Fac output)
};

// The Brick node at p = Vector * Scale. Rows are row_height high (row k covers y in [k h, (k+1) h));
// bricks are brick_width wide along x, shifted and squashed per row by `rows`; the mortar covers
// the band of width mortar_size inside each brick's edges, blended over the inner part of it
// (mortar_smooth: the fraction of the band that blends; 0: a hard edge).
BrickSample brick(const Vec3& p, float mortar_size, float mortar_smooth, float bias, float brick_width,
                  float row_height, const BrickRows& rows);

// The Brick node's Color: the brick colour mix(color1, color2, tint) (Color1 itself where the mortar
// is complete), then mix(brick colour, mortar colour, mortar).
Vec3 brick_color(const BrickSample& s, const Vec3& color1, const Vec3& color2, const Vec3& mortar_color);

// ---- Magic ---------------------------------------------------------------------------------------
constexpr int kMagicDepths = 11;  // Depth 0..10

// The Magic node's Color (its Fac is the colour's average, (r + g + b) * (1/3)). p's coordinates
// are reduced modulo 2 pi (float's 2 pi, fmod), then three waves of their sums times 5 * scale are
// distorted `depth` times, each step replacing one component by a sine or cosine of a signed sum of
// the three, scaled by distortion; the result is 0.5 - v / (2 distortion) (0.5 - v for distortion
// 0). Depths beyond 10 are 10, below 0 are 0.
Vec3 magic(const Vec3& p, float scale, int depth, float distortion);

// ---- the ops (see above for their inputs) --------------------------------------------------------
OpValue checker_op(const ShaderOpContext& c);
OpValue gradient_op(const ShaderOpContext& c);
OpValue brick_op(const ShaderOpContext& c);
OpValue magic_op(const ShaderOpContext& c);

// The op's output by its flags: bit 0 set, the Fac as a float; clear, the colour.
constexpr uint8_t kTextureFac = 1;

}  // namespace torrance::shader
