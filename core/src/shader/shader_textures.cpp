#include "torrance/shader/shader_textures.h"

#include "torrance/util/smoothstep.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace torrance::shader {

namespace {

// Every step below is one float operation in the order Cycles does it, so results round as Cycles'.

// A float to int as Cycles' (int)f on x86 (cvttss2si): truncation; NaN and values outside int's
// range give INT_MIN.
int32_t to_int(float f) {
  if (!(f >= -2147483648.0f && f < 2147483648.0f)) return INT32_MIN;
  return int32_t(f);
}

int32_t floor_to_int(float f) { return to_int(std::floor(f)); }

// Cycles' clamp to [0, 1]: max then min, each a comparison, so NaN gives 0.
float saturate(float v) {
  const float at_least_0 = v > 0.0f ? v : 0.0f;
  return at_least_0 < 1.0f ? at_least_0 : 1.0f;
}

// 2 pi as Cycles' float constant (6.2831855).
constexpr float kTwoPiFloat = 6.2831853071795864f;

glm::vec4 output(const ShaderOpContext& c, const Vec3& color, float fac) {
  return (c.ins.flags & kTextureFac) ? glm::vec4(fac, 0.0f, 0.0f, 0.0f) : glm::vec4(color, 1.0f);
}

}  // namespace

// ---- Checker -------------------------------------------------------------------------------------

float checker(const Vec3& p) {
  // The parity of |floor(x)|: that of floor(x) itself (two's complement keeps it; INT_MIN is even).
  const auto odd = [](float x) { return (uint32_t(floor_to_int((x + 0.000001f) * 0.999999f)) & 1u) != 0u; };
  const bool same_xy = odd(p.x) == odd(p.y);
  return same_xy == odd(p.z) ? 1.0f : 0.0f;
}

// ---- Gradient ------------------------------------------------------------------------------------

namespace {

// The spherical types' radius: 0 from just inside the unit sphere out (the 0.999999 keeps a unit
// vector at exactly 0).
float sphere_falloff(const Vec3& p) {
  const float length = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
  return std::fmax(0.999999f - length, 0.0f);
}

float gradient_unclamped(GradientType type, const Vec3& p) {
  switch (type) {
    case GradientType::Linear: return p.x;
    case GradientType::Quadratic: {
      const float r = std::fmax(p.x, 0.0f);
      return r * r;
    }
    case GradientType::Easing: {
      return smooth_step_unclamped(std::fmin(std::fmax(p.x, 0.0f), 1.0f));
    }
    case GradientType::Diagonal: return (p.x + p.y) * 0.5f;
    case GradientType::Spherical: return sphere_falloff(p);
    case GradientType::QuadraticSphere: {
      const float r = sphere_falloff(p);
      return r * r;
    }
    case GradientType::Radial: return std::atan2(p.y, p.x) / kTwoPiFloat + 0.5f;
  }
  return 0.0f;
}

}  // namespace

float gradient(GradientType type, const Vec3& p) { return saturate(gradient_unclamped(type, p)); }

// ---- Brick ---------------------------------------------------------------------------------------

float brick_noise(uint32_t n) {
  n = (n + 1013u) & 0x7fffffffu;
  n ^= n >> 13;
  const uint32_t h = (n * (n * n * 60493u + 19990303u) + 1376312589u) & 0x7fffffffu;
  return 0.5f * (float(h) / 1073741824.0f);
}

BrickSample brick(const Vec3& p, float mortar_size, float mortar_smooth, float bias, float brick_width,
                  float row_height, const BrickRows& rows) {
  const int32_t row = floor_to_int(p.y / row_height);
  float width = brick_width, shift = 0.0f;
  if (rows.offset_frequency > 0 && rows.squash_frequency > 0) {  // rows 0, +-f, +-2f, ...
    if (row % rows.squash_frequency == 0) width = brick_width * rows.squash;
    if (row % rows.offset_frequency == 0) shift = width * rows.offset;
  }
  const float shifted_x = p.x + shift;
  const int32_t column = floor_to_int(shifted_x / width);
  const float x = shifted_x - width * float(column);  // within the brick, from its left edge
  const float y = p.y - row_height * float(row);      // and from its bottom edge

  BrickSample s;
  // The noise's seed: the row in the upper 16 bits, the column's low 16 bits below (wrapping).
  const uint32_t seed = (uint32_t(row) << 16) + (uint32_t(column) & 0xffffu);
  s.tint = saturate(brick_noise(seed) + bias);

  const float a = x < y ? x : y;
  const float b = width - x < row_height - y ? width - x : row_height - y;
  const float edge_distance = a < b ? a : b;
  if (edge_distance >= mortar_size) {
    s.mortar = 0.0f;
  } else if (mortar_smooth == 0.0f) {
    s.mortar = 1.0f;
  } else {
    const float depth = 1.0f - edge_distance / mortar_size;  // 0 at the band's inner edge, 1 at the brick's
    s.mortar = depth < mortar_smooth ? smooth_step_unclamped(depth / mortar_smooth) : 1.0f;
  }
  return s;
}

Vec3 brick_color(const BrickSample& s, const Vec3& color1, const Vec3& color2, const Vec3& mortar_color) {
  Vec3 brick_colour = color1;
  if (s.mortar != 1.0f) brick_colour = (1.0f - s.tint) * color1 + s.tint * color2;
  return brick_colour * (1.0f - s.mortar) + mortar_color * s.mortar;
}

// ---- Magic ---------------------------------------------------------------------------------------

namespace {

// One distortion step: component `target` becomes sign * wave(sx x + sy y + sz z) * distortion, the
// wave a cosine or a sine (the signs' +-1 products are exact, so the sums round as written out).
struct MagicStep {
  int target;
  bool cosine;
  float sign, sx, sy, sz;
};

constexpr std::array<MagicStep, kMagicDepths - 1> kMagicSteps = {{
    {1, true, -1.0f, 1.0f, -1.0f, 1.0f},    // depth 1 (after x, y and z are scaled by distortion)
    {0, true, 1.0f, 1.0f, -1.0f, -1.0f},    // 2
    {2, false, 1.0f, -1.0f, -1.0f, -1.0f},  // 3
    {0, true, -1.0f, -1.0f, 1.0f, -1.0f},   // 4
    {1, false, -1.0f, -1.0f, 1.0f, 1.0f},   // 5
    {1, true, -1.0f, -1.0f, 1.0f, 1.0f},    // 6
    {0, true, 1.0f, 1.0f, 1.0f, 1.0f},      // 7
    {2, false, 1.0f, 1.0f, 1.0f, -1.0f},    // 8
    {0, true, -1.0f, -1.0f, -1.0f, 1.0f},   // 9
    {1, false, -1.0f, 1.0f, -1.0f, 1.0f},   // 10
}};

}  // namespace

Vec3 magic(const Vec3& p, float scale, int depth, float distortion) {
  // Reduced first, so that huge coordinates keep sin and cos finite and a large one does not drown
  // the others' phases.
  const float px = std::fmod(p.x, kTwoPiFloat), py = std::fmod(p.y, kTwoPiFloat), pz = std::fmod(p.z, kTwoPiFloat);
  Vec3 v(std::sin((px + py + pz) * 5.0f * scale), std::cos((-px + py - pz) * 5.0f * scale),
         -std::cos((-px - py + pz) * 5.0f * scale));
  const int steps = std::clamp(depth, 0, kMagicDepths - 1);
  if (steps > 0) v *= distortion;
  for (int k = 0; k < steps; ++k) {
    const MagicStep& s = kMagicSteps[size_t(k)];
    const float arg = s.sx * v.x + s.sy * v.y + s.sz * v.z;
    v[s.target] = s.sign * (s.cosine ? std::cos(arg) : std::sin(arg)) * distortion;
  }
  if (distortion != 0.0f) v /= distortion * 2.0f;
  return Vec3(0.5f) - v;
}

// ---- the ops -------------------------------------------------------------------------------------

OpValue checker_op(const ShaderOpContext& c) {
  const float f = checker(c.vector(0) * c.value(3));
  return output(c, f == 1.0f ? c.vector(1) : c.vector(2), f);
}

OpValue gradient_op(const ShaderOpContext& c) {
  const float f = gradient(GradientType(c.ins.mode), c.vector(0));
  return output(c, Vec3(f), f);
}

namespace {

// A frequency from its register: an int as Cycles converts, in 0..99 (Blender's range is 1..99).
int frequency(float f) { return std::clamp(to_int(f), 0, 99); }

}  // namespace

OpValue brick_op(const ShaderOpContext& c) {
  const glm::vec4& settings = c.in(10);
  const BrickRows rows{settings.x, frequency(settings.y), settings.z, frequency(settings.w)};
  const BrickSample s =
      brick(c.vector(0) * c.value(4), c.value(5), c.value(6), c.value(7), c.value(8), c.value(9), rows);
  return output(c, brick_color(s, c.vector(1), c.vector(2), c.vector(3)), s.mortar);
}

OpValue magic_op(const ShaderOpContext& c) {
  const Vec3 color = magic(c.vector(0), c.value(1), int(c.ins.mode), c.value(2));
  return output(c, color, (color.x + color.y + color.z) * (1.0f / 3.0f));
}

}  // namespace torrance::shader
