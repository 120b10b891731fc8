// Point clouds as spheres (Scene::add_points): what a point set stores, as Cycles (3.1+) renders
// a point cloud: each point a sphere of its radius about its centre (kernel/geom/point_intersect.h).
#pragma once

#include "torrance/scene/scene.h"

#include <glm/vec4.hpp>

#include <vector>

namespace torrance {

struct Scene::PointSet {
  std::vector<glm::vec4> points;  // centre x, y, z and radius per point (Embree's FLOAT4 buffer)
  // Per-point attributes the shader programs read (Attribute op; Point Info's Random is one):
  // point i's layer a at i * attribute_ids.size() + a, then two rows of zeros, since a hit hands
  // them to the Attribute op as a triangle's corners 0, 1, 2 at weights (1, 0, 0).
  std::vector<Vec3> attributes;
  std::vector<int32_t> attribute_ids;
  uint32_t material = 0;
  bool emits = false;       // its material emits: hits on it carry kUnsampledEmitter
  ObjectSettings settings;  // its object's (Scene::set_points_settings)
};

}  // namespace torrance
