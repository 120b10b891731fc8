// Blender 5.0+'s Radial Tiling node as Cycles computes it (kernel/svm/radial_tiling.h and
// radial_tiling_shared.h of Cycles 5.3), for whole Sides, and fractional Sides at Roundness 0:
// the plane around the origin cut into Sides segments (a rounded regular polygon's), each point
// given its segment's coordinates.
//
// In float32, Cycles' order: the point's angle A from the x axis in [0, 2 pi), the segment's half
// angle h = pi / Sides (Sides at least 2, Roundness clamped to [0, 1]), the segment id
// floor(A / 2h) and the angle a within it; the polygon's bevel starts h - atan((1 - Roundness)
// tan h) from a segment divider. Per point (x, y, z, w) = (the distance along the segment's angle
// bisector in polygon units, the signed parameter across it, the segment's width, its rotation):
//   Roundness 0: the straight polygon; 1: circles (the distance is the point's length);
//   between: a rounded part near the dividers (a circle of radius Roundness through the bevel,
//   the parameter a quadratic spline into it) and the straight part between;
//   fractional Sides (Roundness 0): the last, narrower segment with its own bisector.
// The parameter is 0 at the origin; Normalize maps it to [0, 1], else 1 is taken off the distance.
// Outputs: Segment Coordinates (parameter, distance, 0), Segment ID floor(Sides (atan2(y, x) /
// 2 pi + [y < 0])), Segment Width, Segment Rotation.
//
// Not done: fractional Sides with Roundness above 0 (Cycles' irregular rounded segment); the
// add-on reports such a node (it reads Sides and Roundness as constants for that), and the op
// computes it as Roundness 0. The Python twin is python_addon/torrance/shader_graph/radial_tiling.py.
#pragma once

#include "torrance/util/math.h"
#include "torrance/shader/shader_program.h"

namespace torrance::shader {

// (distance, parameter, width, rotation) before the outputs' mapping; sides >= 2, roundness in
// [0, 1].
glm::vec4 radial_tiling(const Vec2& coord, float sides, float roundness, bool normalize);
float radial_tiling_segment_id(const Vec2& coord, float sides);

// ---- the op (ShaderOpcode 62) ----
//
// RadialTiling  in: Vector (xy), Sides (x), Roundness (x); flags & 1: Normalize;
//               mode 0: Segment Coordinates (parameter, distance, 0, 0);
//               mode 1: (Segment ID, Segment Width, Segment Rotation, 0)
constexpr int kRadialTilingModes = 2;
OpValue radial_tiling_op(const ShaderOpContext& c);

}  // namespace torrance::shader
