// The shader graph's vector nodes (opcodes 104-111), as Cycles 3.4 computes them
// (svm/mapping_util.h, vector_rotate.h):
//   Mapping (104)       mode 0 Point, 1 Texture, 2 Vector, 3 Normal; in0 Vector, in1 Location,
//                       in2 Rotation (Euler XYZ, radians), in3 Scale
//   VectorRotate (105)  mode 0 Axis Angle, 1 X, 2 Y, 3 Z, 4 Euler XYZ; flags & 1: Invert;
//                       in0 Vector, in1 Center, in2 Axis, in3.x Angle, in4 Rotation
#pragma once

#include "torrance/shader_program.h"

namespace torrance::shader {

// Cycles' rotation of Euler angles (X, then Y, then Z) as the rows of a matrix.
glm::mat3 euler_rows(const Vec3& euler);
Vec3 mapping(int type, const Vec3& vector, const Vec3& location, const Vec3& rotation, const Vec3& scale);
Vec3 vector_rotate(int type, bool invert, const Vec3& vector, const Vec3& center, const Vec3& axis, float angle,
                   const Vec3& rotation);

glm::vec4 mapping_op(const ShaderOpContext& c);
glm::vec4 vector_rotate_op(const ShaderOpContext& c);

}  // namespace torrance::shader
