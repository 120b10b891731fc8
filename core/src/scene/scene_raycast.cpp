// The Raycast node's query (ShaderTracer::raycast): the first surface along a ray, in the whole
// scene (Scene::intersect, every surface whatever its material) or, for Only Local, in the
// object's own BVH (scene_local.cpp's local scenes). The triangle the ray leaves is passed by
// as Cycles' self-intersection skip does: the query starts again just past that hit.
#include "scene/embree_rays.h"
#include "scene/scene_internal.h"

#include <algorithm>
#include <cmath>

namespace torrance {

using namespace scene_detail;

namespace {

// A ray from the hit meets the hit's own triangle near t = 0, wherever rounding puts it, and
// again after a restart just past it: each restart starts past the last hit by a step that
// grows (from ~1e-7 of the scene's scale over |dir|, eightfold each time), at most this often.
constexpr int kMaxSkips = 8;

float first_skip_step(const Vec3& origin, const Vec3& dir) {
  const float scale = std::max(1.0f, std::max(std::abs(origin.x), std::max(std::abs(origin.y), std::abs(origin.z))));
  return 1e-7f * scale / glm::length(dir);
}

bool skipped(const SurfaceHit& h, uint32_t skip_object, uint32_t skip_prim) {
  return skip_object != ShaderGlobals::kNoObject && h.object == skip_object && h.prim == skip_prim;
}

// The hit as the node reads it: Cycles' N at the hit, turned toward the ray's origin when the
// ray meets the triangle's back (its geometric normal along the ray).
RaycastHit raycast_hit(const SurfaceHit& h, const Vec3& dir) {
  const bool back = glm::dot(h.geometric_normal, dir) > 0.0f;
  return RaycastHit{h.t, back ? -h.shading_normal : h.shading_normal, h.object};
}

}  // namespace

bool Scene::raycast(const Vec3& origin, const Vec3& dir, float tmin, float tmax, uint32_t only_object,
                    uint32_t skip_object, uint32_t skip_prim, RaycastHit& hit) const {
  if (!(glm::dot(dir, dir) > 0.0f) || !(tmin < tmax)) return false;
  SurfaceHit h;
  if (only_object == ShaderGlobals::kNoObject) {
    Ray ray{origin, dir, tmin, tmax};
    float step = first_skip_step(origin, dir);
    for (int k = 0; k <= kMaxSkips; ++k, step *= 8.0f) {
      if (!intersect(ray, h)) return false;
      if (!skipped(h, skip_object, skip_prim)) {
        hit = raycast_hit(h, dir);
        return true;
      }
      ray.tmin = std::max(h.t, ray.tmin) + step;
      if (!(ray.tmin < ray.tmax)) return false;
    }
    return false;
  }
  Vec3 o = origin, d = dir;  // the object's space (an instance's prototype's): the same t
  const RTCScene scene = static_cast<RTCScene>(local_scene(only_object, o, d));
  if (!scene) return false;
  float from = tmin, step = first_skip_step(origin, dir);
  for (int k = 0; k <= kMaxSkips; ++k, step *= 8.0f) {
    RTCRayHit rh = embree_ray_hit(o, d, from, tmax);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    h.t = rh.ray.tfar;
    h.object = only_object;
    h.prim = rh.hit.primID;
    if (!skipped(h, skip_object, skip_prim)) {
      triangle_hit(only_object, rh.hit.primID, rh.hit.u, rh.hit.v, dir, h);
      h.t = rh.ray.tfar;
      hit = raycast_hit(h, dir);
      return true;
    }
    from = std::max(h.t, from) + step;
    if (!(from < tmax)) return false;
  }
  return false;
}

}  // namespace torrance
