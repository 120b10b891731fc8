// Emissive triangles as one light for next-event estimation: a triangle is chosen in proportion
// to its power (area x emitted luminance), then a point uniformly on it. Both faces emit, as in
// Cycles. BSDF-sampled rays find emitters as ordinary surface hits; the integrator then weights
// them with pdf() for MIS.
#pragma once

#include "torrance/lights_common.h"

#include <functional>
#include <vector>

namespace torrance {

struct EmissiveTriangle {
  Vec3 p0, edge1, edge2;
  Vec3 normal;  // unit
  float area;
  Vec2 uv0, uv1, uv2;
  uint32_t material;
};

class MeshLight {
 public:
  // Emitted radiance of `material` at `uv` (textures applied).
  using EmissionLookup = std::function<Vec3(uint32_t material, const Vec2& uv)>;
  // power[i] > 0 is the selection weight of triangle i.
  MeshLight(std::vector<EmissiveTriangle> triangles, const std::vector<float>& power, EmissionLookup emission);

  LightSample sample(const Vec3& p, const Vec3& n, const Vec2& u) const;
  float importance(const Vec3& p, const Vec3& n) const;
  bool hit(const Vec3&, const Vec3&, const Vec3&, float, LightHit&) const { return false; }
  // Solid-angle density with which sample(p, ...) produces point q on triangle `index`.
  float pdf(size_t index, const Vec3& p, const Vec3& q) const;
  size_t size() const { return triangles_.size(); }

 private:
  std::vector<EmissiveTriangle> triangles_;
  std::vector<float> cdf_;  // size + 1
  EmissionLookup emission_;
  float total_power_;
  Vec3 center_;
  float radius_;
};

}  // namespace torrance
