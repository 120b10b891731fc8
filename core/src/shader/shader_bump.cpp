#include "torrance/shader/shader_bump.h"

#include "torrance/shader/shader_vector.h"
#include "torrance/bsdfs/shading_normal.h"

#include <algorithm>
#include <cmath>

namespace torrance::shader {
namespace {

// v / |v|, or 0 when v has no finite direction.
Vec3 unit_or_zero(const Vec3& v) {
  const float len = glm::length(v);
  return len > 0.0f && std::isfinite(len) ? v / len : Vec3(0.0f);
}

bool is_zero(const Vec3& v) { return v.x == 0.0f && v.y == 0.0f && v.z == 0.0f; }

}  // namespace

void differential_axes(const Vec3& n, Vec3& a, Vec3& b) {
  if (n.x != n.y || n.x != n.z) a = Vec3(n.z - n.y, n.x - n.z, n.y - n.x);
  else a = Vec3(n.z - n.y, n.x + n.z, -n.y - n.x);
  a = unit_or_zero(a);
  b = glm::cross(n, a);
}

Vec3 bump_normal(const Vec3& n, const Vec3& dx, const Vec3& dy, float h_c, float h_x, float h_y, float distance,
                 float strength, float filter_width) {
  // The surface's tangents scaled so that (h_x - h_c) rx + (h_y - h_c) ry is det times the
  // height's gradient in the tangent plane times the filter width (the heights' step).
  const Vec3 rx = glm::cross(dy, n), ry = glm::cross(n, dx);
  const float det = glm::dot(dx, rx);
  const Vec3 gradient = (h_x - h_c) * rx + (h_y - h_c) * ry;
  const Vec3 bumped =
      unit_or_zero(filter_width * std::abs(det) * n - distance * (det < 0.0f ? -1.0f : 1.0f) * gradient);
  if (is_zero(bumped)) return n;
  const float s = std::max(strength, 0.0f);
  const Vec3 mixed = unit_or_zero(s * bumped + (1.0f - s) * n);
  return is_zero(mixed) ? n : mixed;
}

Vec3 mix_mapped_normal(const Vec3& n, const Vec3& mapped, float strength) {
  Vec3 out = mapped;
  if (strength != 1.0f) out = unit_or_zero(n + (mapped - n) * std::max(strength, 0.0f));
  return is_zero(out) ? n : out;
}

Vec3 tangent_normal_map(const Vec3& c, const Vec3& n, const Vec3& tangent, float bitangent_sign, float strength,
                        bool cycles4) {
  // The tangent made perpendicular to n (as a mesh's per-vertex tangents are to its normals).
  const Vec3 t = unit_or_zero(tangent - glm::dot(tangent, n) * n);
  if (is_zero(t)) return n;
  const Vec3 b = bitangent_sign * glm::cross(n, t);
  Vec3 m = 2.0f * (c - Vec3(0.5f));
  if (!cycles4) return mix_mapped_normal(n, unit_or_zero(m.x * t + m.y * b + m.z * n), strength);
  m.x *= strength;
  m.y *= strength;
  m.z = 1.0f + std::clamp(strength, 0.0f, 1.0f) * (m.z - 1.0f);
  const Vec3 mapped = unit_or_zero(m.x * t + m.y * b + m.z * n);
  return is_zero(mapped) ? n : mapped;
}

OpValue bump_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  Vec3 n = unit_or_zero(c.vector(5));
  if (is_zero(n)) n = g.normal;
  const float distance = (c.ins.flags & kBumpInvert) ? -c.value(1) : c.value(1);
  const Vec3 out = bump_normal(n, g.dpdx, g.dpdy, c.value(2), c.value(3), c.value(4), distance, c.value(0), c.value(6));
  if (c.ins.flags & kBumpCycles4) return glm::vec4(out, 0.0f);
  return glm::vec4(valid_shading_normal(g.true_normal, out, g.incoming), 0.0f);
}

OpValue normal_map_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  const float side = g.backfacing ? -1.0f : 1.0f;
  const Vec3 color = c.vector(0);
  const float strength = c.value(1);
  if (c.ins.mode == 0) {  // the frame as the mesh winds it, the result facing the viewer
    const Vec3 n = side * g.normal;
    const bool cycles4 = (c.ins.flags & kNormalMapCycles4) != 0;
    return glm::vec4(side * tangent_normal_map(color, n, g.tangent, g.bitangent_sign, strength, cycles4), 0.0f);
  }
  Vec3 m = 2.0f * (color - Vec3(0.5f));
  if (c.ins.mode == 2 || c.ins.mode == 4) m = Vec3(m.x, -m.y, -m.z);
  m = c.ins.mode >= 3 ? ObjectTransform(c, 2).normal(m) : unit_or_zero(m);
  return glm::vec4(mix_mapped_normal(g.normal, side * m, strength), 0.0f);
}

OpValue displacement_op(const ShaderOpContext& c) {
  const float amount = (c.value(0) - c.value(1)) * c.value(2);
  if (c.ins.mode == 1) return glm::vec4(c.vector(3) * amount, 0.0f);
  const ObjectTransform object(c, 4);
  return glm::vec4(object.direction(object.inverse_normal(c.vector(3)) * amount), 0.0f);
}

OpValue vector_displacement_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  Vec3 d = (c.vector(0) - Vec3(c.value(1))) * c.value(2);
  const ObjectTransform object(c, 3);
  if (c.ins.mode == 0) {  // the frame in object space, as Cycles' tangent attribute is
    const Vec3 n = object.inverse_normal(g.normal);
    Vec3 t = unit_or_zero(object.inverse_direction(g.tangent));
    t = unit_or_zero(t - glm::dot(t, n) * n);
    const Vec3 b = g.bitangent_sign * unit_or_zero(glm::cross(n, t));
    d = t * d.x + n * d.y + b * d.z;
  }
  return glm::vec4(c.ins.mode == 2 ? d : object.direction(d), 0.0f);
}

}  // namespace torrance::shader
