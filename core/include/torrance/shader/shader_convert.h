// Blender's converter nodes as Cycles 3.4 computes them (kernel/svm/ramp.h, map_range.h, clamp.h,
// blackbody.h, wavelength.h), in single precision like its kernel: ColorRamp, RGB Curves, Vector
// Curves, Float Curve, Map Range (float and vector), Clamp, Blackbody and Wavelength. The add-on's
// constant folder has a twin of every function here (python_addon/torrance/shader_graph/
// convert_ops.py); both are checked against one table of cases, core/tests/data/
// shader_convert_cases.json, whose cases Blender 3.4.1's Cycles rendered.
//
// Ramps and curves are tables the add-on bakes as Cycles' Blender sync does, with Blender's own
// evaluation (ColorRamp.evaluate, CurveMapping.evaluate), at kRampTableSize evenly spaced
// positions: a ColorRamp's RGBA at i / 255; a curve's values at min_x + i / 255 (max_x - min_x),
// where min_x and max_x are the smallest first and the largest last point x of its curves (for
// RGB Curves, R, G and B are baked through the combined curve C: R(C(x))). A lookup (ramp_lookup)
// interpolates linearly between entries; ColorRamp's Constant interpolation takes the entry below
// (so its stops fall on the 1/255 grid); positions outside the table clamp to its ends, or, for a
// curve whose mapping extrapolates (CurveMapping.extend 'EXTRAPOLATED'), continue the slope of its
// two end entries.
//
// Edge cases that are Cycles' and kept on purpose:
//   - A NaN position reads the table's first entry (Cycles' saturate sends NaN to 0).
//   - Map Range (float) gives 0, not To Min, when From Min == From Max; its Clamp clamps the
//     result to the To range whatever the interpolation (Cycles adds a Clamp node in Range mode),
//     so such a 0 becomes To Min or To Max. Stepped's factor is floor(f (steps + 1)) / steps, so a
//     value at From Max maps past To Max (1.25 for 4 steps) unless clamped; steps <= 0 give To Min.
//     Smooth Step reverses for From Min > From Max as 1 - smoothstep(From Max, From Min, value).
//   - Map Range (vector) divides per component with 0 for a zero divisor (To Min); its Clamp
//     applies to Linear and Stepped only.
//   - Clamp (Min Max) with Min > Max gives Max; Range swaps them.
//   - Blackbody is a piecewise fit in Rec. 709 between 800 and 12000 K, constant outside (below
//     800 K its red is 5.4), negative channels clamped to 0. Wavelength interpolates the CIE 1931
//     colour-matching functions tabulated every 5 nm from 380 to 780 nm, which are black outside;
//     Cycles truncates the table index toward 0, so 375-380 nm extrapolate the first interval.
//     Both assume Blender's default colour management (scene linear = Rec. 709).
#pragma once

#include "torrance/util/math.h"
#include "torrance/shader/shader_program.h"

#include <cstdint>

namespace torrance::shader {

// Cycles' RAMP_TABLE_SIZE: the entries of every baked ramp or curve.
constexpr int kRampTableSize = 256;

// A lookup in a table of `entries` entries of `stride` (1 to 4) floats at position f in [0, 1]
// (Cycles' ramp lookup): the entries' components in the first `stride` of the result, the rest 0.
// No entries give 0; one entry gives it everywhere.
glm::vec4 ramp_lookup(const float* table, int entries, int stride, float f, bool interpolate, bool extrapolate);

// ColorRamp: table = RGBA entries (4 floats each); interpolate = false for Constant.
glm::vec4 color_ramp(const float* table, int size, float fac, bool interpolate);

// RGB Curves and Vector Curves: table = min_x, max_x, then RGB (XYZ) entries; each channel looks
// up its own column at (c - min_x) / (max_x - min_x); the result is mixed with c by fac.
Vec3 curves(const float* table, int size, float fac, const Vec3& c, bool extrapolate);

// Float Curve: table = min_x, max_x, then the values.
float float_curve(const float* table, int size, float fac, float value, bool extrapolate);

// Map Range's interpolation_type, in Blender's order.
enum class MapRangeMode : uint8_t { Linear, Stepped, SmoothStep, SmootherStep };
constexpr int kMapRangeModeCount = 4;

float map_range(MapRangeMode mode, float value, float from_min, float from_max, float to_min, float to_max,
                float steps, bool clamp);
Vec3 vector_map_range(MapRangeMode mode, const Vec3& value, const Vec3& from_min, const Vec3& from_max,
                      const Vec3& to_min, const Vec3& to_max, const Vec3& steps, bool clamp);

// Clamp's clamp_type, in Blender's order.
enum class ClampMode : uint8_t { MinMax, Range };
float clamp(ClampMode mode, float value, float min, float max);

// Blackbody: the colour of a black body at `kelvin`, in scene linear Rec. 709.
Vec3 blackbody(float kelvin);
// Wavelength: the colour of light of `nanometres`, in scene linear Rec. 709.
Vec3 wavelength(float nanometres);
// The CIE 1931 2-degree colour-matching functions (x, y, z) at `nanometres`: the 5 nm table from
// 380 to 780 nm interpolated linearly (0 outside; below 380 the first interval extrapolated to 375).
Vec3 cie_1931(float nanometres);
// CIE XYZ (D65) -> scene linear Rec. 709, Cycles 3.4's xyz_to_rgb of the default configuration.
Vec3 xyz_to_rec709(const Vec3& xyz);

// The ops (ShaderOpcode 72-80), each reading what its ShaderOpcode's comment says.
OpValue color_ramp_op(const ShaderOpContext& c);
OpValue rgb_curves_op(const ShaderOpContext& c);
OpValue vector_curves_op(const ShaderOpContext& c);
OpValue float_curve_op(const ShaderOpContext& c);
OpValue map_range_op(const ShaderOpContext& c);
OpValue vector_map_range_op(const ShaderOpContext& c);
OpValue clamp_op(const ShaderOpContext& c);
OpValue blackbody_op(const ShaderOpContext& c);
OpValue wavelength_op(const ShaderOpContext& c);

}  // namespace torrance::shader
