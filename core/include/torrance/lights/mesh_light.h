// Emissive triangles as one light for next-event estimation: a triangle is chosen in proportion
// to its power (area x emitted luminance), then a point uniformly on it. Both faces emit, as in
// Cycles. BSDF-sampled rays find emitters as ordinary surface hits; the integrator then weights
// them with pdf() for MIS.
#pragma once

#include "torrance/lights/lights_common.h"
#include "torrance/integrator/path_state.h"

#include <functional>
#include <vector>

namespace torrance {

struct EmissiveTriangle {
  Vec3 p0, edge1, edge2;
  Vec3 normal;  // unit
  float area;
  uint32_t material;
  // Where it comes from: a Scene mesh or instance (Scene::triangle_hit's owner), its triangle,
  // and whether the corners above are that triangle's in mirrored order (u and v swapped).
  uint32_t owner = 0, prim = 0;
  bool mirrored = false;
  int8_t light_group = -1;  // its object's (extra_passes.h), -1: none
  uint8_t emitter_links = 0;  // its object's entry of the light linking table (light_linking.h)
  bool moving = false;      // motion blur: its corners above are the frame's (MeshLight::MovingTriangle)
};

// p0, edges, unit normal and area of a triangle of corners p[0..2]; false for no area.
bool place_emissive_triangle(EmissiveTriangle& t, const Vec3& p0, const Vec3& p1, const Vec3& p2);

class MeshLight {
 public:
  // Radiance emitted back along unit wi by the point at barycentrics b (along edge1 and edge2)
  // of a triangle, seen by a path in state `seen_by` (Cycles' next-event estimation: kRayEmission,
  // ray_length the distance).
  using EmissionLookup =
      std::function<Vec3(const EmissiveTriangle& triangle, const Vec2& b, const Vec3& wi, const PathState& seen_by)>;
  // Motion blur: a moving triangle where the thread's ray time puts it (Cycles' light sampling of
  // motion triangles: triangle_world_space_vertices at the path's time).
  using MovingTriangle = std::function<EmissiveTriangle(const EmissiveTriangle& triangle)>;
  // power[i] > 0 is the selection weight of triangle i (the frame's: a moving triangle keeps it).
  MeshLight(std::vector<EmissiveTriangle> triangles, const std::vector<float>& power, EmissionLookup emission,
            MovingTriangle moving = nullptr);

  // receiver: the path's state at p (the emitter's shader sees it with kRayEmission).
  LightSample sample(const Vec3& p, const Vec3& n, const Vec2& u, const PathState& receiver = {}) const;
  float importance(const Vec3& p, const Vec3& n) const;
  bool hit(const Vec3&, const Vec3&, const Vec3&, float, LightHit&) const { return false; }
  // Solid-angle density with which sample(p, ...) produces point q on triangle `index`.
  float pdf(size_t index, const Vec3& p, const Vec3& q) const;
  size_t size() const { return triangles_.size(); }

 private:
  // Triangle t, or where it is at the ray's time if it moves (into `moved`).
  const EmissiveTriangle& at_time(const EmissiveTriangle& t, EmissiveTriangle& moved) const {
    if (!t.moving) return t;
    moved = moving_(t);
    return moved;
  }

  std::vector<EmissiveTriangle> triangles_;
  std::vector<float> cdf_;  // size + 1
  EmissionLookup emission_;
  MovingTriangle moving_;
  float total_power_;
  Vec3 center_;
  float radius_;
};

}  // namespace torrance
