#include "media/equiangular_aim.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace torrance {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Whether origin + t dir lies inside the cone (its forward nappe).
bool in_cone(const LightReach& r, const Vec3& origin, const Vec3& dir, float t) {
  const Vec3 v = origin + dir * t - r.apex;
  const float along = glm::dot(v, r.axis);
  return along >= 0.0f && along * along >= r.cos_half * r.cos_half * glm::dot(v, v);
}

// The interval of the line inside a convex cone (half-angle below 90 degrees): between the roots of
// (v.a + t d.a)^2 = cos^2 |v + t d|^2 and where the line crosses the apex's plane, the pieces whose
// midpoints are inside. Empty: t0 > t1.
void cone_interval(const LightReach& r, const Vec3& origin, const Vec3& dir, float& t0, float& t1) {
  const Vec3 v = origin - r.apex;
  const float va = glm::dot(v, r.axis), da = glm::dot(dir, r.axis), c2 = r.cos_half * r.cos_half;
  const double a = double(da) * da - c2, b = 2.0 * (double(va) * da - c2 * double(glm::dot(v, dir)));
  const double c = double(va) * va - c2 * double(glm::dot(v, v));
  std::array<float, 5> cuts{};
  int n = 0;
  if (std::abs(a) > 1e-12) {
    const double disc = b * b - 4.0 * a * c;
    if (disc >= 0.0) {
      const double root = std::sqrt(disc), q = -0.5 * (b + std::copysign(root, b));
      cuts[size_t(n++)] = float(q / a);
      if (q != 0.0) cuts[size_t(n++)] = float(c / q);
    }
  } else if (std::abs(b) > 1e-12) {
    cuts[size_t(n++)] = float(-c / b);
  }
  if (std::abs(da) > 1e-12f) cuts[size_t(n++)] = -va / da;
  std::sort(cuts.begin(), cuts.begin() + n);
  float lo = kInf, hi = -kInf;
  for (int i = 0; i <= n; ++i) {  // the pieces (-inf, c0), (c0, c1), ..., (c_{n-1}, inf)
    const float start = i == 0 ? -kInf : cuts[size_t(i - 1)], end = i == n ? kInf : cuts[size_t(i)];
    const float probe = std::isinf(start) ? (std::isinf(end) ? 0.0f : end - 1.0f - std::abs(end))
                        : std::isinf(end) ? start + 1.0f + std::abs(start)
                                          : 0.5f * (start + end);
    if (!(end > start) || !in_cone(r, origin, dir, probe)) continue;
    lo = std::min(lo, start);
    hi = std::max(hi, end);
  }
  t0 = std::max(t0, lo);
  t1 = std::min(t1, hi);
}

LightReach reach_of(const PointLight& light) {
  LightReach reach;
  const SpotShape& spot = light.spot();
  // Spots of 180 degrees or more (and not spots) shine everywhere; a cone of half-angle below 90
  // degrees is convex, its apex moved back along the axis until it holds the light's sphere.
  if (!light.is_spot() || !(spot.cos_half_angle > 1e-3f)) return reach;
  const float sin_half = std::sqrt(std::max(1.0f - spot.cos_half_angle * spot.cos_half_angle, 0.0f));
  if (!(sin_half > 1e-6f)) return reach;
  reach.kind = LightReach::Kind::Cone;
  reach.axis = spot.axis;
  reach.cos_half = spot.cos_half_angle;
  reach.apex = light.position() - spot.axis * (light.radius() / sin_half);
  return reach;
}

LightReach reach_of(const AreaLight& light) {
  LightReach reach;
  reach.kind = LightReach::Kind::Front;
  reach.apex = light.center();
  reach.axis = light.normal();
  return reach;
}

// The integral of 1 / r^2 along [t0, t1] of the line seen from point: the angle it subtends there
// over the point's distance to the line (floored at min_distance: a light on the line).
float inverse_square_integral(const Vec3& origin, const Vec3& dir, const Vec3& point, float t0, float t1,
                              float min_distance) {
  const Vec3 to_point = point - origin;
  const float delta = glm::dot(to_point, dir);
  const float d = std::max(glm::length(to_point - dir * delta), min_distance);
  const float angle = std::atan((t1 - delta) / d) - std::atan((t0 - delta) / d);
  return std::max(angle, 0.0f) / d;
}

}  // namespace

bool LightReach::narrow(const Vec3& origin, const Vec3& dir, float& t0, float& t1) const {
  if (kind == Kind::Cone) {
    cone_interval(*this, origin, dir, t0, t1);
  } else if (kind == Kind::Front) {
    const float height = glm::dot(origin - apex, axis), rate = glm::dot(dir, axis);
    if (rate > 0.0f) t0 = std::max(t0, -height / rate);
    else if (rate < 0.0f) t1 = std::min(t1, -height / rate);
    else if (!(height > 0.0f)) return false;
  }
  return t1 > t0;
}

size_t aimable_lights(const Lights& lights) {
  size_t aimable = 0;
  for (size_t i = 0; i < lights.count(); ++i) aimable += lights.point(i) || lights.area(i);
  return aimable;
}

bool choose_aim(const Lights& lights, const Vec3& origin, const Vec3& dir, float tmin, float t_max, float u,
                AimTarget& out) {
  // Two passes over the lights (no allocation): the total weight, then the one u falls in.
  auto weight_of = [&](size_t i, AimTarget& target) {
    const PointLight* point = lights.point(i);
    const AreaLight* area = lights.area(i);
    if (!point && !area) return 0.0f;
    target.point = point ? point->position() : area->center();
    target.reach = point ? reach_of(*point) : reach_of(*area);
    float t0 = tmin, t1 = t_max;
    if (!target.reach.narrow(origin, dir, t0, t1)) return 0.0f;
    const float size = point ? point->radius() : area->extent();
    const float intensity = point ? point->intensity_luminance() : area->intensity_luminance();
    const float w = intensity * inverse_square_integral(origin, dir, target.point, t0, t1, std::max(size, 1e-4f));
    return std::isfinite(w) ? w : 0.0f;
  };
  AimTarget target;
  double total = 0.0;
  for (size_t i = 0; i < lights.count(); ++i) total += weight_of(i, target);
  if (!(total > 0.0)) return false;
  const double goal = double(u) * total;
  double run = 0.0;
  size_t last = lights.count();
  for (size_t i = 0; i < lights.count(); ++i) {
    const float w = weight_of(i, target);
    if (!(w > 0.0f)) continue;
    last = i;
    run += w;
    if (goal < run) {
      out = target;
      return true;
    }
  }
  if (last == lights.count()) return false;
  weight_of(last, out);  // rounding left u past the sum: the last light that can shine
  return true;
}

}  // namespace torrance
