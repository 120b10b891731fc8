#include "torrance/shader/shader_vector.h"

#include "torrance/shader/shader_hash.h"

#include <cmath>

namespace torrance::shader {
namespace {

// Row r of the matrix times v (Cycles' transform_direction), and the transposed product.
Vec3 times(const glm::mat3& rows, const Vec3& v) {
  return Vec3(glm::dot(rows[0], v), glm::dot(rows[1], v), glm::dot(rows[2], v));
}
Vec3 times_transposed(const glm::mat3& rows, const Vec3& v) { return v.x * rows[0] + v.y * rows[1] + v.z * rows[2]; }

Vec3 safe_divide(const Vec3& a, const Vec3& b) {
  return Vec3(b.x != 0.0f ? a.x / b.x : 0.0f, b.y != 0.0f ? a.y / b.y : 0.0f, b.z != 0.0f ? a.z / b.z : 0.0f);
}
Vec3 safe_normalize(const Vec3& a) {
  const float len = glm::length(a);
  return len != 0.0f ? a * (1.0f / len) : a;
}

// Rodrigues' rotation of p about a unit axis, term by term as Cycles writes it.
Vec3 rotate_around_axis(const Vec3& p, const Vec3& a, float angle) {
  const float c = std::cos(angle), s = std::sin(angle), k = 1.0f - c;
  return Vec3((c + k * a.x * a.x) * p.x + (k * a.x * a.y - a.z * s) * p.y + (k * a.x * a.z + a.y * s) * p.z,
              (k * a.x * a.y + a.z * s) * p.x + (c + k * a.y * a.y) * p.y + (k * a.y * a.z - a.x * s) * p.z,
              (k * a.x * a.z - a.y * s) * p.x + (k * a.y * a.z + a.x * s) * p.y + (c + k * a.z * a.z) * p.z);
}

// The cosine and sine of an angle; a zero angle (the usual Mapping's) without the library's
// calls: cos(+-0) is 1 and sin(+-0) the zero itself, the values the calls return.
void cos_sin(float angle, float* c, float* s) {
  if (angle == 0.0f) {
    *c = 1.0f;
    *s = angle;
  } else {
    *c = std::cos(angle);
    *s = std::sin(angle);
  }
}

}  // namespace

glm::mat3 euler_rows(const Vec3& e) {
  // No rotation (the usual Mapping's, all three +0): the rows the products below give for
  // cosines 1 and sines +0, the third row's first -0 (the sine negated).
  if (float_bits(e.x) == 0u && float_bits(e.y) == 0u && float_bits(e.z) == 0u)
    return glm::mat3(Vec3(1.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f), Vec3(-0.0f, 0.0f, 1.0f));
  float cx, cy, cz, sx, sy, sz;
  cos_sin(e.x, &cx, &sx);
  cos_sin(e.y, &cy, &sy);
  cos_sin(e.z, &cz, &sz);
  glm::mat3 rows;
  rows[0] = Vec3(cy * cz, sy * sx * cz - cx * sz, sy * cx * cz + sx * sz);
  rows[1] = Vec3(cy * sz, sy * sx * sz + cx * cz, sy * cx * sz - sx * cz);
  rows[2] = Vec3(-sy, cy * sx, cy * cx);
  return rows;
}

Vec3 mapping(int type, const Vec3& vector, const Vec3& location, const Vec3& rotation, const Vec3& scale) {
  const glm::mat3 r = euler_rows(rotation);
  switch (type) {
    case 0: return times(r, vector * scale) + location;
    case 1: return safe_divide(times_transposed(r, vector - location), scale);
    case 2: return times(r, vector * scale);
    default: return safe_normalize(times(r, safe_divide(vector, scale)));
  }
}

Vec3 vector_rotate(int type, bool invert, const Vec3& vector, const Vec3& center, const Vec3& axis, float angle,
                   const Vec3& rotation) {
  if (type == 4) {
    const glm::mat3 r = euler_rows(rotation);
    return (invert ? times_transposed(r, vector - center) : times(r, vector - center)) + center;
  }
  const Vec3 a = type == 1 ? Vec3(1.0f, 0.0f, 0.0f) : type == 2 ? Vec3(0.0f, 1.0f, 0.0f)
               : type == 3 ? Vec3(0.0f, 0.0f, 1.0f) : axis;
  const float len = type == 0 ? glm::length(a) : 1.0f;
  if (len == 0.0f) return vector;
  return rotate_around_axis(vector - center, a / len, invert ? -angle : angle) + center;
}

Vec3 safe_unit(const Vec3& v) {
  const float len = glm::length(v);
  return len > 0.0f && std::isfinite(len) ? v / len : Vec3(0.0f);
}

ObjectTransform::ObjectTransform(const ShaderOpContext& c, int first) {
  const glm::mat3 m(c.vector(first), c.vector(first + 1), c.vector(first + 2));
  const float det = glm::determinant(m);
  if (det == 0.0f || !std::isfinite(det)) return;
  matrix = m;
  inverse = glm::inverse(m);
  location = c.vector(first + 3);
  known = true;
}

Vec3 ObjectTransform::normal(const Vec3& n) const { return safe_unit(known ? glm::transpose(inverse) * n : n); }
Vec3 ObjectTransform::inverse_normal(const Vec3& n) const { return safe_unit(known ? glm::transpose(matrix) * n : n); }

namespace {

// A 3 x 4 transform given by its rows (w the translation) of a point (w 1) or a direction (w 0).
Vec3 through_rows(const glm::vec4 rows[3], const Vec3& v, float w) {
  const glm::vec4 p(v, w);
  return Vec3(glm::dot(rows[0], p), glm::dot(rows[1], p), glm::dot(rows[2], p));
}

// The 3 x 3 part of rows, transposed, times v (Cycles' transform_direction_transposed).
Vec3 through_columns(const glm::vec4 rows[3], const Vec3& v) {
  return Vec3(rows[0]) * v.x + Vec3(rows[1]) * v.y + Vec3(rows[2]) * v.z;
}

}  // namespace

Vec3 vector_transform(int mode, const Vec3& v, const ObjectTransform& object, const glm::vec4 to_camera[3],
                      const glm::vec4 to_world[3], bool cycles4_normals) {
  enum { kWorld, kObject, kCamera };
  const int type = mode / 9, from = mode / 3 % 3, to = mode % 3;
  const bool direction = type != 0;
  const bool normal4 = type == 2 && cycles4_normals;
  const float w = direction ? 0.0f : 1.0f;
  auto into_object = [&](const Vec3& x) {
    if (normal4) return object.inverse_normal(x);
    return direction ? object.inverse_direction(x) : object.inverse_point(x);
  };
  auto out_of_object = [&](const Vec3& x) {
    if (normal4) return object.normal(x);
    return direction ? object.direction(x) : object.point(x);
  };
  // Cycles 4.x moves a normal by the inverse transpose: world -> camera by camera -> world's rows
  // transposed, and back by world -> camera's.
  auto into_camera = [&](const Vec3& x) {
    return normal4 ? safe_unit(through_columns(to_world, x)) : through_rows(to_camera, x, w);
  };
  auto out_of_camera = [&](const Vec3& x) {
    return normal4 ? safe_unit(through_columns(to_camera, x)) : through_rows(to_world, x, w);
  };
  Vec3 out = v;
  if (from == kWorld) {
    if (to == kCamera) out = into_camera(out);
    else if (to == kObject) out = into_object(out);
  } else if (from == kCamera) {
    if (to != kCamera) out = out_of_camera(out);
    if (to == kObject) out = into_object(out);
  } else {
    if (to != kObject) out = out_of_object(out);
    if (to == kCamera) out = into_camera(out);
  }
  return type == 2 && !normal4 ? safe_unit(out) : out;
}

OpValue vector_transform_op(const ShaderOpContext& c) {
  const ObjectTransform object(c, 1);
  const glm::vec4 to_camera[3] = {c.in(5), c.in(6), c.in(7)};
  const glm::vec4 to_world[3] = {c.in(8), c.in(9), c.in(10)};
  return glm::vec4(vector_transform(c.ins.mode, c.vector(0), object, to_camera, to_world, c.ins.flags & 2),
                   0.0f);
}

OpValue mapping_op(const ShaderOpContext& c) {
  return glm::vec4(mapping(c.ins.mode, c.vector(0), c.vector(1), c.vector(2), c.vector(3)), 0.0f);
}

OpValue vector_rotate_op(const ShaderOpContext& c) {
  return glm::vec4(vector_rotate(c.ins.mode, c.ins.flags & 1, c.vector(0), c.vector(1), c.vector(2), c.value(3),
                                 c.vector(4)),
                   0.0f);
}

}  // namespace torrance::shader
