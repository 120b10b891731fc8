// The Curves Info node (Cycles' svm_node_hair_info and its curve attributes; opcode 112): on a
// hair strand's hit (ShaderGlobals::on_curve, primitive_info), mode
//   0 Is Strand   1
//   1 Intercept   the arc length along the strand's keys to the hit over its length: 0 root, 1 tip
//   2 Length      the strand's length (its key polyline's)
//   3 Thickness   twice the radius, the segment's two key radii interpolated linearly
//   4 Tangent Normal  the view direction made perpendicular to the strand (ShaderGlobals::tangent)
//   5 Random      the strand's random value (Cycles: its index hashed)
// and 0 (all of them) on anything else. Value outputs in x, Tangent Normal in xyz.
#pragma once

#include "torrance/shader/shader_program.h"

namespace torrance::shader {

constexpr int kCurvesInfoModes = 6;
OpValue curves_info_op(const ShaderOpContext& c);

// The Point Info node (Cycles' svm_node_point_info; opcode 113): on a point's hit
// (ShaderGlobals::on_point, primitive_info), mode
//   0 Position  the point's centre, world space (xyz)
//   1 Radius    its radius, world space (x)
// and 0 on anything else. Its Random is an attribute of the point set, as in Cycles (the
// add-on's ('point_random',) layer: the point's index hashed), read by the Attribute op.
constexpr int kPointInfoModes = 2;
OpValue point_info_op(const ShaderOpContext& c);

}  // namespace torrance::shader
