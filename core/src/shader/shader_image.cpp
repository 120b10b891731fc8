#include "torrance/shader/shader_image.h"

#include "torrance/shader/shader_vector.h"

#include <algorithm>
#include <cmath>

namespace torrance::shader {

namespace {

constexpr float kPi = 3.14159265358979323846f;

float clamp01(float v) { return std::min(std::max(v, 0.0f), 1.0f); }

// Cycles' remap of a 0..1 box to -1..1 before the sphere and tube maps.
Vec3 remap_square(const Vec3& co) { return (co - Vec3(0.5f)) * 2.0f; }

}  // namespace

Vec2 map_to_sphere(const Vec3& co) {
  const float l = glm::dot(co, co);
  if (!(l > 0.0f)) return Vec2(0.0f);
  const float u = co.x == 0.0f && co.y == 0.0f ? 0.0f : 0.5f - std::atan2(co.x, co.y) * (0.5f / kPi);
  const float c = std::min(std::max(co.z / std::sqrt(l), -1.0f), 1.0f);
  return Vec2(u, 1.0f - std::acos(c) * (1.0f / kPi));
}

Vec2 map_to_tube(const Vec3& co) {
  const float len = std::sqrt(co.x * co.x + co.y * co.y);
  if (!(len > 0.0f)) return Vec2(0.0f);
  return Vec2((1.0f - std::atan2(co.x / len, co.y / len) / kPi) * 0.5f, (co.z + 1.0f) * 0.5f);
}

Vec3 box_weights(const Vec3& signed_n, float blend) {
  // The normal's absolute components as barycentric coordinates of a triangle whose corners
  // are the faces x, y and z: near a corner one face alone, near an edge two blending, in the
  // middle (when blending) all three.
  Vec3 n = glm::abs(signed_n);
  const float sum = n.x + n.y + n.z;
  if (!(sum > 0.0f)) return Vec3(1.0f, 0.0f, 0.0f);
  n /= sum;
  const float limit = 0.5f * (1.0f + blend);
  if (n.x > limit * (n.x + n.y) && n.x > limit * (n.x + n.z)) return Vec3(1.0f, 0.0f, 0.0f);
  if (n.y > limit * (n.x + n.y) && n.y > limit * (n.y + n.z)) return Vec3(0.0f, 1.0f, 0.0f);
  if (n.z > limit * (n.x + n.z) && n.z > limit * (n.y + n.z)) return Vec3(0.0f, 0.0f, 1.0f);
  if (!(blend > 0.0f)) return Vec3(1.0f, 0.0f, 0.0f);  // no face clearly wins: one side, as Cycles
  auto edge = [&](float a, float b) { return clamp01((a / (a + b) - 0.5f * (1.0f - blend)) / blend); };
  if (n.z < (1.0f - limit) * (n.y + n.x)) {
    const float w = edge(n.x, n.y);
    return Vec3(w, 1.0f - w, 0.0f);
  }
  if (n.x < (1.0f - limit) * (n.y + n.z)) {
    const float w = edge(n.y, n.z);
    return Vec3(0.0f, w, 1.0f - w);
  }
  if (n.y < (1.0f - limit) * (n.x + n.z)) {
    const float w = edge(n.x, n.z);
    return Vec3(w, 0.0f, 1.0f - w);
  }
  auto corner = [&](float a) { return ((2.0f - limit) * a + (limit - 1.0f)) / (2.0f * limit - 1.0f); };
  return Vec3(corner(n.x), corner(n.y), corner(n.z));
}

Vec2 direction_to_equirectangular(const Vec3& co) {
  const float l = glm::length(co);
  if (!(l > 0.0f)) return Vec2(0.0f);
  const Vec3 d = co / l;
  const float c = std::min(std::max(d.z / glm::length(d), -1.0f), 1.0f);
  return Vec2((std::atan2(d.y, d.x) - kPi) / (-2.0f * kPi), (std::acos(c) - kPi) / -kPi);
}

Vec2 direction_to_mirror_ball(const Vec3& co) {
  const float l = glm::length(co);
  Vec3 d = l > 0.0f ? co / l : Vec3(0.0f);
  d.y -= 1.0f;
  const float div = 2.0f * std::sqrt(std::max(-0.5f * d.y, 0.0f));
  if (div > 0.0f) d /= div;
  return Vec2(0.5f * (d.x + 1.0f), 0.5f * (d.z + 1.0f));
}

OpValue image_projection_op(const ShaderOpContext& c) {
  const Vec3 co = c.vector(0);
  switch (c.ins.mode) {
    case 0: return glm::vec4(map_to_sphere(remap_square(co)), 0.0f, 0.0f);
    case 1: return glm::vec4(map_to_tube(remap_square(co)), 0.0f, 0.0f);
    case 6: return glm::vec4(direction_to_equirectangular(co), 0.0f, 0.0f);
    case 7: return glm::vec4(direction_to_mirror_ball(co), 0.0f, 0.0f);
    default: break;
  }
  // The normal in object space, as Cycles' object_inverse_normal_transform: by M's transpose.
  const Vec3 m = ObjectTransform(c, 2).inverse_normal(c.vector(1));
  switch (c.ins.mode) {
    case 2: return glm::vec4(m.x < 0.0f ? 1.0f - co.y : co.y, co.z, 0.0f, 0.0f);
    case 3: return glm::vec4(m.y > 0.0f ? 1.0f - co.x : co.x, co.z, 0.0f, 0.0f);
    case 4: return glm::vec4(m.z > 0.0f ? 1.0f - co.y : co.y, co.x, 0.0f, 0.0f);
    default: return glm::vec4(box_weights(m, c.value(6)), 0.0f);
  }
}

}  // namespace torrance::shader
