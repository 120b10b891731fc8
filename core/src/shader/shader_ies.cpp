// The IES Texture node's evaluation (shader_ies.h), in float and in the order of Cycles 3.4's
// kernel_ies_interp.
#include "torrance/shader/shader_ies.h"

#include <algorithm>
#include <cmath>

namespace torrance::shader {

namespace {

constexpr float kPi = 3.1415926535897932f;
// Cycles 4.x's wrap tests, in float: pi - 1e-7 and 2 pi - 1e-7 round back to pi and 2 pi.
constexpr float kWrapEps = 1e-7f;
constexpr float kNearPi = kPi - kWrapEps;
constexpr float kNearTwoPi = 2.0f * kPi - kWrapEps;

// Catmull-Rom between b and c (a and d the neighbours), x in [0, 1]: Cycles' cubic_interp.
float catmull_rom(float a, float b, float c, float d, float x) {
  return 0.5f * (((d + 3.0f * (b - c) - a) * x + (2.0f * a - 5.0f * b + 4.0f * c - d)) * x + (c - a)) * x + b;
}

float fraction(float a, float b, float x) { return b != a ? (x - a) / (b - a) : 0.0f; }

// Which neighbours past the table's ends a lookup wraps (Cycles 3.4: the first vertical one
// mirrored, the last clamped, the horizontal ones always round the circle).
struct Wraps {
  bool low = true, high = false, clamp_high = true, around = true;
};

// The intensity of row h interpolated over the vertical angles at v + frac.
float vertical(const float* rows, int h, int v, int v_num, float frac, const Wraps& w) {
  const float* row = rows + size_t(h) * size_t(v_num);
  const float before = v > 0 ? row[v - 1] : (w.low ? row[1] : 0.0f);
  float after = 0.0f;
  if (w.clamp_high)
    after = row[std::min(v + 2, v_num - 1)];
  else if (v + 2 < v_num)
    after = row[v + 2];
  else if (w.high)
    after = row[v_num - 2];
  return catmull_rom(before, row[v], row[v + 1], after, frac);
}

}  // namespace

float ies_intensity(const float* table, int size, float h, float v, IesLookup lookup) {
  if (size < 2) return 0.0f;
  const float h_count = table[0], v_count = table[1];
  if (!(h_count >= 2.0f && v_count >= 1.0f && h_count < 1e6f && v_count < 1e6f)) return 0.0f;
  const int h_num = int(h_count), v_num = int(v_count);
  if (size != 2 + h_num + v_num + h_num * v_num) return 0.0f;
  const float* h_angles = table + 2;
  const float* v_angles = h_angles + h_num;
  const float* rows = v_angles + v_num;
  if (v_num < 2 || !(v < v_angles[v_num - 1])) return 0.0f;  // past the last vertical angle (or NaN)
  Wraps w;
  if (lookup == IesLookup::Cycles4) {
    const float h_low = h_angles[0], h_high = h_angles[h_num - 1];
    if (v < v_angles[0] || h < h_low || h >= h_high) return 0.0f;
    w.low = v_angles[0] < kWrapEps;
    w.high = v_angles[v_num - 1] > kNearPi;
    w.around = h_low < kWrapEps && h_high > kNearTwoPi;
    w.clamp_high = false;
  }
  int h_i = 0, v_i = 0;
  while (h_i + 2 < h_num && h_angles[h_i + 1] < h) ++h_i;
  while (v_i + 2 < v_num && v_angles[v_i + 1] < v) ++v_i;
  const float h_frac = fraction(h_angles[h_i], h_angles[h_i + 1], h);
  const float v_frac = fraction(v_angles[v_i], v_angles[v_i + 1], v);
  // The horizontal angles cover the circle, the last (2 pi) repeating the first: the
  // neighbours wrap past it.
  const float a = h_i > 0 ? vertical(rows, h_i - 1, v_i, v_num, v_frac, w)
                  : (w.around ? vertical(rows, h_num - 2, v_i, v_num, v_frac, w) : 0.0f);
  const float b = vertical(rows, h_i, v_i, v_num, v_frac, w);
  const float c = vertical(rows, h_i + 1, v_i, v_num, v_frac, w);
  const float d = h_i + 2 < h_num ? vertical(rows, h_i + 2, v_i, v_num, v_frac, w)
                  : (w.around ? vertical(rows, 1, v_i, v_num, v_frac, w) : 0.0f);
  return std::max(catmull_rom(a, b, c, d, h_frac), 0.0f);
}

OpValue ies_op(const ShaderOpContext& c) {
  const Vec3 vector = c.vector(0);
  const float length = glm::length(vector);
  float fac = 0.0f;
  if (length > 0.0f && std::isfinite(length)) {
    const Vec3 d = vector / length;
    const float v = std::acos(std::clamp(-d.z, -1.0f, 1.0f));
    const float h = std::atan2(d.x, d.y) + kPi;
    fac = c.value(1) * ies_intensity(c.data, c.data_size, h, v, IesLookup(c.ins.mode));
  }
  return glm::vec4(fac, 0.0f, 0.0f, 0.0f);
}

}  // namespace torrance::shader
