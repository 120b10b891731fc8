#include "torrance/bsdfs/shading_normal.h"

namespace torrance {

Vec3 valid_shading_normal(const Vec3& ng, const Vec3& ns, const Vec3& wo) {
  const float threshold = std::min(0.9f * glm::dot(ng, wo), 0.01f);
  auto reflection_ok = [&](const Vec3& n) { return glm::dot(ng, 2.0f * glm::dot(wo, n) * n - wo) >= threshold; };
  if (reflection_ok(ns)) return ns;
  float lo = 0.0f, hi = 1.0f;
  for (int i = 0; i < 16; ++i) {
    const float mid = 0.5f * (lo + hi);
    const Vec3 n = glm::mix(ns, ng, mid);
    const float len = glm::length(n);
    if (len > 1e-6f && reflection_ok(n / len)) hi = mid;
    else lo = mid;
  }
  const Vec3 n = glm::mix(ns, ng, hi);
  const float len = glm::length(n);
  return len > 1e-6f ? n / len : ng;
}

DiffuseNormal diffuse_normal(const Frame& frame, const Vec3& checked, const Vec3& unchecked, BrdfModel model) {
  DiffuseNormal d;
  if (model != BrdfModel::PrincipledV2 || checked == unchecked) return d;
  d.n = frame.to_local(unchecked);
  d.tilted = true;
  return d;
}

namespace {
// `n` (world or local) as a unit vector in `frame`, or z where it is degenerate.
Vec3 local_unit(const Frame& frame, const Vec3& n) {
  const Vec3 local = frame.to_local(n);
  const float len = glm::length(local);
  return len > 1e-6f && std::isfinite(len) ? local / len : Vec3(0.0f, 0.0f, 1.0f);
}
}  // namespace

CoatNormal coat_normal(const Frame& frame, const Vec3& checked, const Vec3& ng, const Vec3& coat, const Vec3& wo,
                       const Vec3& closure) {
  CoatNormal c;
  c.unchecked = local_unit(frame, coat);
  c.closure = local_unit(frame, closure);
  c.leans = c.unchecked != c.closure;
  const Vec3 valid = valid_shading_normal(ng, coat, wo);
  if (valid == checked) return c;
  const Vec3 local = frame.to_local(valid);
  const float len = glm::length(local);
  if (!(len > 1e-6f) || !std::isfinite(len)) return c;
  c.frame = Frame(local / len);
  c.tilted = true;
  return c;
}

CoatNormal CoatNormal::sheen_normal(float coat_weight) const {
  CoatNormal s;
  const float w = std::isfinite(coat_weight) ? clamp01(coat_weight) : 0.0f;
  if (!leans) return s;
  const Vec3 n = glm::mix(closure, unchecked, w);
  const float len = glm::length(n);
  if (!(len > 1e-6f) || !std::isfinite(len)) return s;
  const Vec3 unit = n / len;
  if (unit == Vec3(0.0f, 0.0f, 1.0f)) return s;
  s.frame = Frame(unit);
  s.tilted = true;
  return s;
}

}  // namespace torrance
