// Shadow rays: from a shading point to a light sample, and the light they let through (one
// occlusion test, or Cycles' transparent shadows where materials have alpha).
#pragma once

#include "integrator/path_tracer.h"
#include "integrator/thin_wall_shadow.h"
#include "torrance/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace torrance {

// The shadow ray of a light sample: from the offset origin to the sampled point on the light,
// stopping short of it by the same kind of offset, so that a light close to and nearly parallel
// with the surface is neither missed nor self-occluding. tmax <= 0: nothing can be in the way.
inline Ray shadow_ray(const Vec3& p, const Vec3& ng, const LightSample& ls) {
  Ray ray;
  ray.origin = offset_origin(p, ng, ls.wi);
  ray.tmin = 0.0f;
  if (std::isinf(ls.distance)) {
    ray.dir = ls.wi;
    ray.tmax = std::numeric_limits<float>::infinity();
    return ray;
  }
  const Vec3 target = p + ls.wi * ls.distance;
  const Vec3 d = target - ray.origin;
  const float len = glm::length(d);
  const float end_offset = 2e-5f * std::max(1.0f, std::max(std::abs(target.x), std::max(std::abs(target.y),
                                                                                          std::abs(target.z))));
  ray.dir = d / len;
  ray.tmax = len * (1.0f - 1e-4f) - end_offset;
  return ray;
}

// A shadow ray meets a surface at `hit` after `passed` transparent ones and `travelled` metres:
// Cycles' transparent shadows let (1 - alpha) x its transparent colour through (transmittance
// takes it), plus alpha x a smooth thin wall's straight pass (thin_wall_shadow.h); false when the
// surface (or more than max_transparent of them) stops the ray.
inline bool through_transparent_surface(const Scene& scene, const SurfaceHit& hit, const Vec3& dir,
                                        const PathState& receiver, int passed, float travelled, int max_transparent,
                                        Vec3& transmittance) {
  PathState shadow = receiver;  // what a shader sees on the shadow ray (Cycles' shadow path)
  shadow.ray_flags = kRayShadow;
  shadow.transparent_depth = uint8_t(std::min(receiver.transparent_depth + passed, 255));
  shadow.ray_length = travelled + hit.t;
  Vec3 tint;
  const float opacity = scene.opacity(hit, dir, shadow, &tint);
  if (opacity > 0.0f && may_pass_straight(scene, hit.material)) {  // a smooth thin wall under its opaque share
    const Vec3 sheet = straight_through(scene, hit, dir, shadow);
    if (!(max_component(sheet) > 0.0f) && opacity >= 1.0f) return false;
    if (passed >= max_transparent) return false;
    transmittance *= (1.0f - opacity) * tint + opacity * sheet;
    return true;
  }
  if (opacity >= 1.0f || passed >= max_transparent) return false;
  transmittance *= (1.0f - opacity) * tint;
  return true;
}

// The light a shadow ray carries to the shading point: 0 or 1 by one occlusion test, or with
// kAlpha (some material has alpha) Cycles' transparent shadows: each surface in the way with
// alpha < 1 lets (1 - alpha) x its transparent colour through, an opaque one (or more than
// max_transparent_bounces transparent ones) nothing. Found by repeated closest hits, only once
// the occlusion test has found something in the way.
template <bool kAlpha>
Vec3 shadow_transmittance(const Scene& scene, const Vec3& p, const Vec3& ng, const LightSample& ls,
                          int max_transparent, const PathState& receiver = {}) {
  Ray ray = shadow_ray(p, ng, ls);
  if (!(ray.tmax > 0.0f) || !scene.occluded(ray.origin, ray.dir, 0.0f, ray.tmax)) return Vec3(1.0f);
  if (!kAlpha) return Vec3(0.0f);
  Vec3 transmittance(1.0f);
  float travelled = 0.0f;
  for (int passed = 0;; ++passed) {
    SurfaceHit hit;
    if (!scene.intersect(ray, hit)) return transmittance;
    if (!through_transparent_surface(scene, hit, ray.dir, receiver, passed, travelled, max_transparent, transmittance))
      return Vec3(0.0f);
    if (!(max_component(transmittance) > 0.0f)) return Vec3(0.0f);
    ray.origin = offset_origin(hit.position, hit.geometric_normal, ray.dir);
    ray.tmax -= hit.t;
    travelled += hit.t;
    if (!(ray.tmax > 0.0f)) return transmittance;
  }
}

// The light a shadow ray towards a shadow-linked emitter (lights/light_linking.h) lets through:
// surfaces that are not among the emitter's blockers are passed as if absent; the blockers stop
// it, or with alpha let their transparency through as in shadow_transmittance.
inline Vec3 linked_shadow_transmittance(const Scene& scene, const Vec3& p, const Vec3& ng, const LightSample& ls,
                                        uint64_t shadow_sets, int max_transparent, const PathState& receiver = {}) {
  Ray ray = shadow_ray(p, ng, ls);
  Vec3 transmittance(1.0f);
  float travelled = 0.0f;
  for (int passed = 0; ray.tmax > 0.0f;) {
    SurfaceHit hit;
    if (!scene.intersect(ray, hit)) break;
    if (blocks_shadow(shadow_sets, hit.object_settings.blocker_set)) {
      if (!through_transparent_surface(scene, hit, ray.dir, receiver, passed++, travelled, max_transparent,
                                       transmittance) ||
          !(max_component(transmittance) > 0.0f))
        return Vec3(0.0f);
    }
    ray.origin = offset_origin(hit.position, hit.geometric_normal, ray.dir);
    ray.tmax -= hit.t;
    travelled += hit.t;
  }
  return transmittance;
}

}  // namespace torrance
