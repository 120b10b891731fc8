// Small vector helpers shared by the core: GLM types, constants, an orthonormal frame.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace torrance {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Mat4 = glm::mat4;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 1.0f / kPi;
inline constexpr float kTwoPi = 2.0f * kPi;

inline float luminance(const Vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
inline float max_component(const Vec3& c) { return std::max(c.r, std::max(c.g, c.b)); }
// Of a weight that may be signed (heterogeneous media's unbiased tracking, media/varying_tracking.h).
// Written out (not via glm::abs, whose functor layers kept it from being inlined in the path loop).
inline float max_abs_component(const Vec3& c) {
  return std::max(std::abs(c.r), std::max(std::abs(c.g), std::abs(c.b)));
}
inline bool is_finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline float clamp01(float x) { return std::min(std::max(x, 0.0f), 1.0f); }
inline float safe_sqrt(float x) { return std::sqrt(std::max(x, 0.0f)); }
inline float sqr(float x) { return x * x; }

// Orthonormal basis around a unit normal (Duff et al. 2017 branchless construction).
struct Frame {
  Vec3 s, t, n;

  Frame() : s(1, 0, 0), t(0, 1, 0), n(0, 0, 1) {}
  explicit Frame(const Vec3& normal) : n(normal) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    s = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    t = Vec3(b, sign + n.y * n.y * a, -n.y);
  }
  Vec3 to_local(const Vec3& v) const { return Vec3(glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)); }
  Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace torrance
