// The shader graph's vector nodes (opcodes 104-111), as Cycles 3.4 computes them
// (svm/mapping_util.h, vector_rotate.h):
//   Mapping (104)       mode 0 Point, 1 Texture, 2 Vector, 3 Normal; in0 Vector, in1 Location,
//                       in2 Rotation (Euler XYZ, radians), in3 Scale
//   VectorRotate (105)  mode 0 Axis Angle, 1 X, 2 Y, 3 Z, 4 Euler XYZ; flags & 1: Invert;
//                       in0 Vector, in1 Center, in2 Axis, in3.x Angle, in4 Rotation
//   VectorTransform (108) (svm/vector_transform.h) mode (type * 3 + from) * 3 + to, type 0
//                       Point, 1 Vector, 2 Normal (moved as a vector, then normalised, as 3.4
//                       does; flags & 2: as Cycles 4.x, see vector_transform), spaces 0 World, 1 Object, 2 Camera; in0 Vector, in1-in4 the
//                       object (ObjectTransform), in5-in7 the rows of world -> camera, in8-in10
//                       the rows of camera -> world (3 x 4, w the translation)
#pragma once

#include "torrance/shader/shader_program.h"

namespace torrance::shader {

// Cycles' rotation of Euler angles (X, then Y, then Z) as the rows of a matrix.
glm::mat3 euler_rows(const Vec3& euler);
Vec3 mapping(int type, const Vec3& vector, const Vec3& location, const Vec3& rotation, const Vec3& scale);
Vec3 vector_rotate(int type, bool invert, const Vec3& vector, const Vec3& center, const Vec3& axis, float angle,
                   const Vec3& rotation);

// The hit's object transform, as the add-on passes it to an op: four inputs from `first` on,
// the matrix's columns (the images of the object's x, y and z axes) and its location (per-object
// attribute layers). An all-zero matrix (no per-object constants: instanced prototypes, the
// viewport) is no object: then every transform is the identity, as Cycles' for OBJECT_NONE.
struct ObjectTransform {
  glm::mat3 matrix{1.0f}, inverse{1.0f};
  Vec3 location{0.0f};
  bool known = false;
  ObjectTransform(const ShaderOpContext& c, int first);
  Vec3 point(const Vec3& p) const { return known ? matrix * p + location : p; }
  Vec3 inverse_point(const Vec3& p) const { return known ? inverse * (p - location) : p; }
  Vec3 direction(const Vec3& d) const { return known ? matrix * d : d; }
  Vec3 inverse_direction(const Vec3& d) const { return known ? inverse * d : d; }
  // Cycles' object_normal_transform (normalize(M^-T n)) and its inverse (normalize(M^T n)).
  Vec3 normal(const Vec3& n) const;
  Vec3 inverse_normal(const Vec3& n) const;
};
constexpr int kObjectInputs = 4;

// v / |v|, or 0 when v has no finite direction.
Vec3 safe_unit(const Vec3& v);

constexpr int kVectorTransformModes = 27;
// cycles4_normals (the op's flags & 2, Cycles 4.x): a Normal moves by each transform's inverse
// transpose (ObjectTransform::normal, inverse_normal; the camera's rows transposed), normalised
// at each step, as Cycles 4.x's svm/vector_transform.h; else as a vector, normalised at the end.
Vec3 vector_transform(int mode, const Vec3& v, const ObjectTransform& object, const glm::vec4 to_camera[3],
                      const glm::vec4 to_world[3], bool cycles4_normals = false);

OpValue mapping_op(const ShaderOpContext& c);
OpValue vector_rotate_op(const ShaderOpContext& c);
OpValue vector_transform_op(const ShaderOpContext& c);

}  // namespace torrance::shader
