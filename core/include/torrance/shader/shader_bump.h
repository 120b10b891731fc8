// The Bump and Normal Map nodes (opcodes 16, 17) as Cycles 3.4 computes them (svm/displace.h,
// svm/tex_coord.h), and their formulas, which Scene's image-only bump and normal maps share:
//   Bump (16)       in0.x Strength, in1.x Distance, in2.x the height at the hit, in3.x and in4.x
//                   the height at the hit moved by the ray differentials dx and dy (the add-on
//                   compiles the Height's graph three times, the copies' ops reading the hit
//                   at ShaderInstruction::offset 1 and 2), in5 the Normal input (facing the
//                   viewer), in6.x the Filter Width (Cycles 4.3+; 1 before): a constant, the
//                   offsets' length in ray differentials (one per program: ShaderProgram moves
//                   its offset hits by it); flags & 1: Invert; flags & 2 (kBumpCycles4): Cycles
//                   4.x's, which leaves the reflection check to the closures (3.4 makes the
//                   normal keep reflections above the surface here). Out: the bumped normal,
//                   facing the viewer.
//   NormalMap (17)  in0 Color, in1.x Strength; mode 0 tangent space (the hit's UV tangent),
//                   1 world space, 2 Blender world space (y and z negated), 3 object space,
//                   4 Blender object space (through the object's normal transform); in2-in5
//                   the object (shader_vector.h's ObjectTransform; read in modes 3 and 4).
//                   flags & 1 (kNormalMapCycles4): Cycles 4.x's tangent-space Strength (see
//                   tangent_normal_map). Out: the normal, facing the viewer.
//   Displacement (18)  (svm/displace.h) in0.x Height, in1.x Midlevel, in2.x Scale, in3 Normal,
//                   in4-in7 the object; mode 0 object space (the normal taken to object
//                   space, the offset back to world), 1 world space. Out: the world-space
//                   offset normal * (height - midlevel) * scale.
//   VectorDisplacement (19)  in0 Vector, in1.x Midlevel, in2.x Scale, in3-in6 the object;
//                   mode 0 tangent space ((x, y, z) along the UV tangent, the normal and the
//                   bitangent, in object space), 1 object space, 2 world space. Out: the
//                   world-space offset (vector - midlevel) * scale.
// The add-on renders a Material Output's Displacement as Cycles' "Bump Only": the Bump op of
// the offset's component along the normal, at the hit and its ray-differential offsets.
#pragma once

#include "torrance/shader/shader_program.h"

namespace torrance::shader {

// Cycles' tangent pair around a unit normal (its ray differentials' directions on a surface):
// a = normalize((1, 1, 1) x n) (another axis when n lies along (1, 1, 1)), b = n x a.
void differential_axes(const Vec3& n, Vec3& a, Vec3& b);

// The Bump node's normal: n' = normalize(w |det| n - distance sign(det) g) with
// g = (h_x - h_c) (dy x n) + (h_y - h_c) (n x dx), det = dx . (dy x n), w the filter width (the
// heights h_x, h_y taken at the hit moved by w dx, w dy), mixed with n by strength (clamped at
// 0); n where that has no direction (zero differentials). n: unit.
Vec3 bump_normal(const Vec3& n, const Vec3& dx, const Vec3& dy, float h_c, float h_x, float h_y, float distance,
                 float strength, float filter_width = 1.0f);

// A tangent-space normal map's normal from colour c (0..1 per axis): the colour mapped to
// [-1, 1] over (tangent, sign * n x tangent, n), then mixed with n by strength (clamped at 0).
// n: unit; tangent: unit, or 0 (then n). All three facing one way; the result faces as n.
// cycles4: Cycles 4.x's Strength instead, applied to the mapped colour m before normalising:
// m.x and m.y times strength, m.z moved from 1 towards m.z by strength clamped to [0, 1].
Vec3 tangent_normal_map(const Vec3& c, const Vec3& n, const Vec3& tangent, float bitangent_sign, float strength,
                        bool cycles4 = false);

// The object/world-space mapping's final step: normal `mapped` mixed with n by strength (n
// where that has no direction).
Vec3 mix_mapped_normal(const Vec3& n, const Vec3& mapped, float strength);

OpValue bump_op(const ShaderOpContext& c);
constexpr uint8_t kBumpInvert = 1, kBumpCycles4 = 2, kNormalMapCycles4 = 1;
constexpr int kNormalMapModes = 5;
OpValue normal_map_op(const ShaderOpContext& c);
OpValue displacement_op(const ShaderOpContext& c);
OpValue vector_displacement_op(const ShaderOpContext& c);

}  // namespace torrance::shader
