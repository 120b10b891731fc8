// The one place the Scene's rays reach Embree (Scene::intersect and Scene::occluded call these):
// each query is counted for its thread and, while a RayLog of that scene records, logged with
// its answer (torrance/integrator/ray_log.h).
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>

namespace torrance::ray_queries {

// Motion blur: the time in [0, 1] over the shutter that every query of this thread carries
// (Embree's ray.time) until changed, and at which a moving mesh's hit is interpolated. The
// integrator sets it per camera sample (every ray of the path shares its sample's time); 0
// otherwise, which geometry without motion ignores.
void set_time(float time);
float time();
// The Embree ray mask every query of this thread carries until changed (all bits by default):
// Scene::kCatcherOnlyMask while the catcher-only half of a split path is traced.
void set_mask(uint32_t mask);

// rtcIntersect1 of rh (its hit ids set to invalid by the caller) through scene.
void intersect(RTCScene scene, RTCRayHit& rh);
// rtcIntersect8 of the packet's valid lanes (valid[i] = -1) with the coherent flag.
void intersect_coherent(RTCScene scene, const int* valid, RTCRayHit8& packet);
// rtcOccluded1 of ray through scene; true when something lies in [tnear, tfar].
bool occluded(RTCScene scene, RTCRay& ray);

}  // namespace torrance::ray_queries
