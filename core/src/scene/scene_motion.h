// Motion blur's hit geometry (scene_motion.cpp): a moving mesh's (or deforming prototype's)
// triangle at the ray's time.
#pragma once

#include "scene/scene_internal.h"

namespace torrance::scene_detail {

// A moving mesh's time steps (Scene::Mesh's motion arrays): steps x num_vertices positions and
// steps x num_corners corner normals (nullptr: none).
struct MotionArrays {
  uint32_t steps;
  const Vec3* positions;
  size_t num_vertices;
  const Vec3* corner_normals;
  size_t num_corners;
};

// Overwrites c's positions (and normals, if the mesh has motion normals) with triangle prim's
// (vertices tri) at the thread's ray time (ray_queries::time), interpolated linearly between the
// two time steps around it, as Embree's motion triangles are.
void motion_corners(const MotionArrays& motion, const glm::uvec3& tri, uint32_t prim, Corners& c);

}  // namespace torrance::scene_detail
