// Blender's colour nodes as Cycles 3.4 evaluates them (see shader_color.h). The expressions keep
// Cycles' order of operations, so single-precision results match its kernel's to the rounding of
// the last operation.
#include "torrance/shader/shader_color.h"

#include <cmath>

namespace torrance::shader {

namespace {

// Cycles' scalar min/max: the comparison picks, so max(NaN, 0) is 0.
inline float pick_max(float a, float b) { return a > b ? a : b; }
inline float pick_min(float a, float b) { return a < b ? a : b; }

inline Vec3 lerp(const Vec3& a, const Vec3& b, float t) { return a + t * (b - a); }

inline Vec3 per_channel(const Vec3& a, const Vec3& b, float t, float (*f)(float, float, float)) {
  return Vec3(f(t, a.x, b.x), f(t, a.y, b.y), f(t, a.z, b.z));
}

float screen_channel(float t, float a, float b) {
  return 1.0f - ((1.0f - t) + t * (1.0f - b)) * (1.0f - a);
}

float overlay_channel(float t, float a, float b) {
  const float keep = 1.0f - t;
  if (a < 0.5f) return a * (keep + 2.0f * t * b);
  return 1.0f - (keep + 2.0f * t * (1.0f - b)) * (1.0f - a);
}

float divide_channel(float t, float a, float b) {
  if (b == 0.0f) return a;
  return (1.0f - t) * a + t * a / b;
}

// A zero channel stays 0; otherwise a / (1 - t b), at most 1 (1 where the divisor is <= 0).
float dodge_channel(float t, float a, float b) {
  if (a == 0.0f) return a;
  const float divisor = 1.0f - t * b;
  if (divisor <= 0.0f) return 1.0f;
  const float q = a / divisor;
  return q > 1.0f ? 1.0f : q;
}

// 1 - (1 - a) / (1 - t + t b), within [0, 1] (0 where the divisor is <= 0).
float burn_channel(float t, float a, float b) {
  const float divisor = (1.0f - t) + t * b;
  if (divisor <= 0.0f) return 0.0f;
  const float q = 1.0f - (1.0f - a) / divisor;
  if (q < 0.0f) return 0.0f;
  return q > 1.0f ? 1.0f : q;
}

Vec3 soft_light(float t, const Vec3& a, const Vec3& b) {
  const Vec3 one(1.0f);
  const Vec3 screened = one - (one - b) * (one - a);
  return (1.0f - t) * a + t * ((one - a) * b * a + a * screened);
}

// Hue (and with_saturation: Color) of b on a, blended by t; a as it is where b is grey.
Vec3 take_hue(float t, const Vec3& a, const Vec3& b, bool with_saturation) {
  const Vec3 hsv_b = rgb_to_hsv(b);
  if (hsv_b.y == 0.0f) return a;
  Vec3 hsv = rgb_to_hsv(a);
  hsv.x = hsv_b.x;
  if (with_saturation) hsv.y = hsv_b.y;
  return lerp(a, hsv_to_rgb(hsv), t);
}

Vec3 take_saturation(float t, const Vec3& a, const Vec3& b) {
  Vec3 hsv = rgb_to_hsv(a);
  if (hsv.y == 0.0f) return a;
  hsv.y = (1.0f - t) * hsv.y + t * rgb_to_hsv(b).y;
  return hsv_to_rgb(hsv);
}

Vec3 take_value(float t, const Vec3& a, const Vec3& b) {
  Vec3 hsv = rgb_to_hsv(a);
  hsv.z = (1.0f - t) * hsv.z + t * rgb_to_hsv(b).z;
  return hsv_to_rgb(hsv);
}

Vec3 blend_colors(MixBlend blend, float t, const Vec3& a, const Vec3& b) {
  switch (blend) {
    case MixBlend::MIX:
      return lerp(a, b, t);
    case MixBlend::DARKEN:
      return lerp(a, Vec3(pick_min(a.x, b.x), pick_min(a.y, b.y), pick_min(a.z, b.z)), t);
    case MixBlend::MULTIPLY:
      return lerp(a, a * b, t);
    case MixBlend::BURN:
      return per_channel(a, b, t, burn_channel);
    case MixBlend::LIGHTEN:
      return lerp(a, Vec3(pick_max(a.x, b.x), pick_max(a.y, b.y), pick_max(a.z, b.z)), t);
    case MixBlend::SCREEN:
      return per_channel(a, b, t, screen_channel);
    case MixBlend::DODGE:
      return per_channel(a, b, t, dodge_channel);
    case MixBlend::ADD:
      return lerp(a, a + b, t);
    case MixBlend::OVERLAY:
      return per_channel(a, b, t, overlay_channel);
    case MixBlend::SOFT_LIGHT:
      return soft_light(t, a, b);
    case MixBlend::LINEAR_LIGHT:
      return a + t * (2.0f * b - Vec3(1.0f));
    case MixBlend::DIFFERENCE:
      return lerp(a, glm::abs(a - b), t);
    case MixBlend::EXCLUSION: {
      const Vec3 r = lerp(a, a + b - 2.0f * a * b, t);
      return Vec3(pick_max(r.x, 0.0f), pick_max(r.y, 0.0f), pick_max(r.z, 0.0f));
    }
    case MixBlend::SUBTRACT:
      return lerp(a, a - b, t);
    case MixBlend::DIVIDE:
      return per_channel(a, b, t, divide_channel);
    case MixBlend::HUE:
      return take_hue(t, a, b, false);
    case MixBlend::SATURATION:
      return take_saturation(t, a, b);
    case MixBlend::COLOR:
      return take_hue(t, a, b, true);
    case MixBlend::VALUE:
      return take_value(t, a, b);
  }
  return Vec3(0.0f);
}

}  // namespace

float saturate(float x) { return pick_min(pick_max(x, 0.0f), 1.0f); }

float mix_factor(float fac, bool clamp_factor) { return clamp_factor ? saturate(fac) : fac; }

Vec3 mix_color(MixBlend blend, float fac, const Vec3& a, const Vec3& b, bool clamp_result) {
  const Vec3 r = blend_colors(blend, fac, a, b);
  if (!clamp_result) return r;
  return Vec3(saturate(r.x), saturate(r.y), saturate(r.z));
}

float mix_float(float fac, float a, float b) { return a * (1.0f - fac) + b * fac; }

Vec3 mix_vector(const Vec3& fac, const Vec3& a, const Vec3& b) {
  return a * (Vec3(1.0f) - fac) + b * fac;
}

Vec3 rgb_to_hsv(const Vec3& rgb) {
  const float top = std::fmax(rgb.x, std::fmax(rgb.y, rgb.z));
  const float bottom = pick_min(rgb.x, pick_min(rgb.y, rgb.z));
  const float chroma = top - bottom;
  const float s = top != 0.0f ? chroma / top : 0.0f;
  if (s == 0.0f) return Vec3(0.0f, s, top);

  // Each channel's distance below the maximum, in units of the chroma.
  const Vec3 below = (Vec3(top) - rgb) / chroma;
  float h;
  if (rgb.x == top)
    h = below.z - below.y;
  else if (rgb.y == top)
    h = 2.0f + below.x - below.z;
  else
    h = 4.0f + below.y - below.x;
  h /= 6.0f;
  if (h < 0.0f) h += 1.0f;
  return Vec3(h, s, top);
}

Vec3 hsv_to_rgb(const Vec3& hsv) {
  const float s = hsv.y, v = hsv.z;
  if (s == 0.0f) return Vec3(v);

  // Only a hue of exactly 1 wraps; the sector is floor(6 h), anything but 0 .. 4 counts as 5.
  const float h = (hsv.x == 1.0f ? 0.0f : hsv.x) * 6.0f;
  const float sector = std::floor(h);
  const float f = h - sector;
  const float p = v * (1.0f - s);
  const float q = v * (1.0f - s * f);
  const float t = v * (1.0f - s * (1.0f - f));
  if (sector == 0.0f) return Vec3(v, t, p);
  if (sector == 1.0f) return Vec3(q, v, p);
  if (sector == 2.0f) return Vec3(p, v, t);
  if (sector == 3.0f) return Vec3(p, q, v);
  if (sector == 4.0f) return Vec3(t, p, v);
  return Vec3(v, p, q);
}

Vec3 rgb_to_hsl(const Vec3& rgb) {
  const float top = std::fmax(rgb.x, std::fmax(rgb.y, rgb.z));
  const float bottom = pick_min(rgb.x, pick_min(rgb.y, rgb.z));
  const float l = pick_min(1.0f, (top + bottom) / 2.0f);
  if (top == bottom) return Vec3(0.0f, 0.0f, l);

  const float chroma = top - bottom;
  // Unguarded, as in Cycles: the divisor is 0 for (1.5, 0.5, 0.5) or (1, -1, 0).
  const float s = l > 0.5f ? chroma / (2.0f - top - bottom) : chroma / (top + bottom);
  float h;
  if (top == rgb.x)
    h = (rgb.y - rgb.z) / chroma + (rgb.y < rgb.z ? 6.0f : 0.0f);
  else if (top == rgb.y)
    h = (rgb.z - rgb.x) / chroma + 2.0f;
  else
    h = (rgb.x - rgb.y) / chroma + 4.0f;
  return Vec3(h / 6.0f, s, l);
}

Vec3 hsl_to_rgb(const Vec3& hsl) {
  const float h6 = hsl.x * 6.0f, s = hsl.y, l = hsl.z;
  // Each channel's position on the hue hexagon, in [0, 1].
  const float r = saturate(std::fabs(h6 - 3.0f) - 1.0f);
  const float g = saturate(2.0f - std::fabs(h6 - 2.0f));
  const float b = saturate(2.0f - std::fabs(h6 - 4.0f));
  const float chroma = (1.0f - std::fabs(2.0f * l - 1.0f)) * s;
  return Vec3((r - 0.5f) * chroma + l, (g - 0.5f) * chroma + l, (b - 0.5f) * chroma + l);
}

Vec3 hue_saturation_value(float hue, float saturation, float value, float fac, const Vec3& color) {
  Vec3 hsv = rgb_to_hsv(color);
  hsv.x = std::fmod(hsv.x + hue + 0.5f, 1.0f);  // negative stays negative
  hsv.y = saturate(hsv.y * saturation);
  hsv.z *= value;
  const Vec3 shifted = hsv_to_rgb(hsv);
  Vec3 out;
  for (int i = 0; i < 3; ++i)
    out[i] = pick_max(fac * shifted[i] + (1.0f - fac) * color[i], 0.0f);
  return out;
}

Vec3 invert(float fac, const Vec3& color) {
  Vec3 out;
  for (int i = 0; i < 3; ++i) out[i] = fac * (1.0f - color[i]) + (1.0f - fac) * color[i];
  return out;
}

Vec3 gamma(const Vec3& color, float gamma) {
  if (gamma == 0.0f) return Vec3(1.0f);
  Vec3 out = color;
  for (int i = 0; i < 3; ++i)
    if (out[i] > 0.0f) out[i] = std::pow(out[i], gamma);
  return out;
}

Vec3 bright_contrast(const Vec3& color, float bright, float contrast) {
  const float slope = 1.0f + contrast;
  const float offset = bright - contrast * 0.5f;
  Vec3 out;
  for (int i = 0; i < 3; ++i) out[i] = pick_max(slope * color[i] + offset, 0.0f);
  return out;
}

float rgb_to_bw(const Vec3& color) {
  return color.x * kRgbToY[0] + color.y * kRgbToY[1] + color.z * kRgbToY[2];
}

}  // namespace torrance::shader
