// The colour operations of Blender's shader nodes, as Cycles 3.4 computes them (kernel/svm/
// color_util.h, mix.h, hsv.h, invert.h, gamma.h, brightness.h, convert.h; util/color.h), in
// single precision like the kernel. The add-on's constant folder has a binary64 twin of every
// function here (python_addon/torrance/shader_graph/color_ops.py); both are checked against the
// same table of cases (core/tests/data/shader_color_cases.json).
//
// The factor of a mix, node by node (Cycles 3.4):
//   - MixRGB (legacy ShaderNodeMixRGB): the Fac is always clamped to [0, 1]; "Clamp" (use_clamp)
//     clamps the result. Blender 3.4 turns these nodes into Mix nodes when it opens older files,
//     with clamp_factor on and clamp_result = use_clamp, which computes the same.
//   - Mix (ShaderNodeMix), every data type: the factor is clamped only with clamp_factor (on by
//     default); Clamp Result (colour only) clamps the result.
// mix_factor() is that clamp; mix_color(), mix_float() and mix_vector() take the factor as it
// reaches the blend, so a factor outside [0, 1] extrapolates (or worse, see below).
//
// Edge cases that are Cycles' and kept on purpose:
//   - Clamping (mix_factor, clamp_result) sends NaN to 0, as Cycles' saturate does.
//   - Burn clamps to [0, 1] and Dodge to at most 1 whatever clamp_result says; Dodge leaves a zero
//     channel of a at 0, Divide leaves a's channel where b's is 0; Exclusion (Blender 4.x) clamps
//     below at 0.
//   - Saturation mixes the saturations by the factor and does not blend the result with a; Hue,
//     Saturation and Color leave a unchanged where b (Hue, Color) or a (Saturation) is grey.
//   - rgb_to_hsv: colours with max component 0 (black, and (0, -1, -1)) give (0, 0, 0); negative
//     maxima give negative saturations, which hsv_to_rgb inverts exactly. hsv_to_rgb is not
//     periodic in hue: only h == 1 wraps to 0; any other h outside [0, 1) takes the last (magenta)
//     sector's formula; hsl_to_rgb makes them all red.
//   - rgb_to_hsl clamps the lightness to at most 1 (no round trip above it) and divides by
//     2 - max - min (lightness above 0.5) or max + min (otherwise) unguarded: for instance
//     (1.5, 0.5, 0.5) and (1, -1, 0) give an infinite saturation.
//   - hue_saturation_value clamps negative channels to 0 even at factor 0; its hue shift wraps with
//     fmod, which leaves a negative sum negative (hue inputs below -0.5).
//   - gamma: gamma 0 gives white (1, 1, 1) for any colour; channels <= 0 are left as they are.
#pragma once

#include "torrance/util/math.h"

#include <cstdint>

namespace torrance::shader {

// Blender's blend_type identifiers in the order of its menu (rna_enum_ramp_blend_items).
// Exclusion exists from Blender 4.0 on; Cycles 4.x computes it as implemented here.
enum class MixBlend : uint8_t {
  MIX,
  DARKEN,
  MULTIPLY,
  BURN,
  LIGHTEN,
  SCREEN,
  DODGE,
  ADD,
  OVERLAY,
  SOFT_LIGHT,
  LINEAR_LIGHT,
  DIFFERENCE,
  EXCLUSION,
  SUBTRACT,
  DIVIDE,
  HUE,
  SATURATION,
  COLOR,
  VALUE,
};
constexpr int kMixBlendCount = 19;

// Cycles' saturatef: clamp to [0, 1], NaN -> 0.
float saturate(float x);

// The factor as the node passes it on: clamped to [0, 1] when clamp_factor (MixRGB: always).
float mix_factor(float fac, bool clamp_factor);

// Mix node, colour (and MixRGB): blend a and b by fac; clamp_result clamps the result to [0, 1].
Vec3 mix_color(MixBlend blend, float fac, const Vec3& a, const Vec3& b, bool clamp_result);

// Mix node, float: a (1 - fac) + b fac.
float mix_float(float fac, float a, float b);

// Mix node, vector: a (1 - fac) + b fac per component; a uniform factor is Vec3(fac).
Vec3 mix_vector(const Vec3& fac, const Vec3& a, const Vec3& b);

// Colour models (Separate/Combine Color, Separate/Combine HSV): hue in [0, 1), not degrees.
Vec3 rgb_to_hsv(const Vec3& rgb);
Vec3 hsv_to_rgb(const Vec3& hsv);
Vec3 rgb_to_hsl(const Vec3& rgb);
Vec3 hsl_to_rgb(const Vec3& hsl);

// Hue/Saturation/Value: hue shifts by hue - 0.5, saturation scales (then clamps to [0, 1]),
// value scales; the result blends with the input by fac, negative channels clamp to 0.
Vec3 hue_saturation_value(float hue, float saturation, float value, float fac, const Vec3& color);

// Invert Color: fac (1 - c) + (1 - fac) c per channel (fac not clamped).
Vec3 invert(float fac, const Vec3& color);

// Gamma: c^gamma for channels > 0; gamma 0 gives (1, 1, 1).
Vec3 gamma(const Vec3& color, float gamma);

// Brightness/Contrast: max((1 + contrast) c + bright - contrast / 2, 0) per channel.
Vec3 bright_contrast(const Vec3& color, float bright, float contrast);

// RGB to BW and the implicit colour -> float conversion: the luminance Y of the scene-linear
// colour. Cycles reads the weights off the OCIO config; Blender 3.4's default config (Linear =
// Rec.709 primaries) gives the Rec.709/sRGB Y row below (measured in Cycles 3.4: 0.212673,
// 0.715153, 0.0721754).
inline constexpr float kRgbToY[3] = {0.2126729f, 0.7151522f, 0.0721750f};
float rgb_to_bw(const Vec3& color);

}  // namespace torrance::shader
