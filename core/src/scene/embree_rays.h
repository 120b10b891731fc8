// Torrance's rays as Embree's: one place that fills RTCRay / RTCRayHit and the lanes of a
// packet (origin, direction, [tmin, tmax], no time or mask, hit ids invalid), for the Scene's
// queries (scene.cpp, scene_hits.cpp) and the raw-Embree replay (ray_replay.cpp).
#pragma once

#include "torrance/util/math.h"

#include <embree3/rtcore.h>

namespace torrance {

inline RTCRay embree_ray(const Vec3& origin, const Vec3& dir, float tmin, float tmax) {
  RTCRay ray;
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = dir.x;
  ray.dir_y = dir.y;
  ray.dir_z = dir.z;
  ray.tnear = tmin;
  ray.tfar = tmax;
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  return ray;
}

inline RTCRayHit embree_ray_hit(const Vec3& origin, const Vec3& dir, float tmin, float tmax) {
  RTCRayHit rh;
  rh.ray = embree_ray(origin, dir, tmin, tmax);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// Lane i of a packet (RTCRayHit8 or RTCRayHit16); the lane's ray id is i.
template <class RayHitN>
void set_embree_lane(RayHitN& packet, int i, const Vec3& origin, const Vec3& dir, float tmin, float tmax) {
  packet.ray.org_x[i] = origin.x;
  packet.ray.org_y[i] = origin.y;
  packet.ray.org_z[i] = origin.z;
  packet.ray.dir_x[i] = dir.x;
  packet.ray.dir_y[i] = dir.y;
  packet.ray.dir_z[i] = dir.z;
  packet.ray.tnear[i] = tmin;
  packet.ray.tfar[i] = tmax;
  packet.ray.time[i] = 0.0f;
  packet.ray.mask[i] = 0xFFFFFFFFu;
  packet.ray.id[i] = uint32_t(i);
  packet.ray.flags[i] = 0;
  packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
  packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
}

}  // namespace torrance
