#include "torrance/lights/mesh_light.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace torrance {

bool place_emissive_triangle(EmissiveTriangle& t, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  t.p0 = p0;
  t.edge1 = p1 - p0;
  t.edge2 = p2 - p0;
  const Vec3 cross = glm::cross(t.edge1, t.edge2);
  t.area = 0.5f * glm::length(cross);
  if (!(t.area > 0.0f) || !std::isfinite(t.area)) return false;
  t.normal = cross / (2.0f * t.area);
  return true;
}

MeshLight::MeshLight(std::vector<EmissiveTriangle> triangles, const std::vector<float>& power, EmissionLookup emission,
                     MovingTriangle moving)
    : triangles_(std::move(triangles)), emission_(std::move(emission)), moving_(std::move(moving)) {
  if (triangles_.empty() || power.size() != triangles_.size())
    throw std::invalid_argument("mesh light needs one positive power per triangle");
  cdf_.assign(triangles_.size() + 1, 0.0f);
  double total = 0.0;
  std::vector<double> running(triangles_.size());
  for (size_t i = 0; i < triangles_.size(); ++i) {
    total += std::max(power[i], 0.0f);
    running[i] = total;
  }
  for (size_t i = 0; i < triangles_.size(); ++i) cdf_[i + 1] = float(running[i] / total);
  cdf_.back() = 1.0f;
  total_power_ = float(total);
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const EmissiveTriangle& t : triangles_)
    for (const Vec3& v : {t.p0, t.p0 + t.edge1, t.p0 + t.edge2}) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
  center_ = 0.5f * (lo + hi);
  radius_ = 0.5f * glm::length(hi - lo);
}

LightSample MeshLight::sample(const Vec3& p, const Vec3&, const Vec2& u, const PathState& receiver) const {
  LightSample s;
  // Choose a triangle with u.x, then reuse what is left of u.x inside its interval.
  const size_t n = triangles_.size();
  const size_t i = std::min(size_t(std::upper_bound(cdf_.begin(), cdf_.end(), u.x) - cdf_.begin()) - 1, n - 1);
  const float span = cdf_[i + 1] - cdf_[i];
  if (!(span > 0.0f)) return s;
  const float ux = std::clamp((u.x - cdf_[i]) / span, 0.0f, 0.99999994f);
  EmissiveTriangle moved;
  const EmissiveTriangle& t = at_time(triangles_[i], moved);
  if (!(t.area > 0.0f)) return s;
  const float su = std::sqrt(ux);
  const float b1 = 1.0f - su, b2 = u.y * su;
  const Vec3 q = t.p0 + b1 * t.edge1 + b2 * t.edge2;
  const Vec3 d = q - p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return s;
  const float dist = std::sqrt(dist2);
  s.wi = d / dist;
  const float cos_light = std::abs(glm::dot(s.wi, t.normal));
  if (!(cos_light > 1e-7f)) return LightSample{};
  s.distance = dist;
  s.pdf = span * dist2 / (t.area * cos_light);
  PathState seen_by = receiver;
  seen_by.ray_flags = kRayEmission;
  seen_by.ray_length = dist;
  s.weight = emission_(t, Vec2(b1, b2), s.wi, seen_by) / s.pdf;
  s.light_group = t.light_group;
  s.emitter_links = t.emitter_links;
  return s;
}

float MeshLight::importance(const Vec3& p, const Vec3&) const {
  const Vec3 d = center_ - p;
  return total_power_ / std::max(glm::dot(d, d), radius_ * radius_ + 1e-8f);
}

float MeshLight::pdf(size_t index, const Vec3& p, const Vec3& q) const {
  EmissiveTriangle moved;
  const EmissiveTriangle& t = at_time(triangles_[index], moved);
  if (!(t.area > 0.0f)) return 0.0f;
  const Vec3 d = q - p;
  const float dist2 = glm::dot(d, d);
  const float cos_light = std::abs(glm::dot(d, t.normal)) / std::sqrt(dist2);
  if (!(cos_light > 1e-7f)) return 0.0f;
  return (cdf_[index + 1] - cdf_[index]) * dist2 / (t.area * cos_light);
}

}  // namespace torrance
