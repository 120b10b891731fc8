// The Image and Environment Texture nodes' projections as Cycles 3.4 computes them (svm/image.h), one op of the
// texture family (opcode 60) that turns the node's Vector into the UVs an Image op reads:
//   ImageProjection (60) in0 Vector; mode
//     0 Sphere: the direction of (Vector - 0.5) * 2 as (longitude, latitude) in [0, 1]
//     1 Tube: its angle about z and (z + 1) / 2
//     2, 3, 4 Box: the UVs of the cube face seen along object x, y, z (mirrored by the side the
//       object-space normal faces, so that no face shows its image flipped)
//     5 Box weights: (wx, wy, wz, 0), each face's share, from the object-space normal and in6.x
//       Blend (0: one face; up to 1: the faces blend across edges and corners)
//     6 Equirectangular, 7 Mirror Ball: the Environment Texture node's projections of the
//       Vector's direction (Cycles' direction_to_equirectangular / direction_to_mirrorball)
//   in1 the shading normal (world), in2-in5 the object (ObjectTransform, shader_vector.h), for
//   the box modes: Cycles projects in object space (the normal by the matrix's transpose).
// The add-on emits one Image op per face and sums them by the weights.
#pragma once

#include "torrance/shader/shader_program.h"

namespace torrance::shader {

constexpr int kImageProjectionModes = 8;

Vec2 map_to_sphere(const Vec3& co);
Vec2 map_to_tube(const Vec3& co);
// Each cube face's weight for a box projection seen along object-space normal n.
Vec3 box_weights(const Vec3& n, float blend);
Vec2 direction_to_equirectangular(const Vec3& co);
Vec2 direction_to_mirror_ball(const Vec3& co);

OpValue image_projection_op(const ShaderOpContext& c);

}  // namespace torrance::shader
