#include "media/medium_walk.h"

#include "integrator/shadow_rays.h"
#include "media/varying_tracking.h"

#include <algorithm>
#include <limits>

namespace torrance {

namespace {

constexpr int kMaxBoundaries = 1024;  // Cycles' VOLUME_BOUNDS_MAX

}  // namespace

MediumWalk walk_media(const Scene& scene, Ray& ray, SurfaceHit& hit, bool& found, MediumStack& stack,
                      Vec3& throughput, SobolSampler& sampler, bool may_scatter, float& passed_length) {
  const SceneMedia& media = scene.media();
  MediumWalk walk;
  for (int crossed = 0;; ++crossed) {
    const float t_end = found ? hit.t : std::numeric_limits<float>::infinity();
    walk.light_throughput = throughput;
    if (!stack.mix().empty()) {
      const glm::vec4 u = sampler.next_4d();
      FreeFlight f;
      if (stack.mix().varies()) {
        Rng rng = tracking_rng(u.z, u.w);
        f = track_free_flight(scene, stack.mix(), ray.origin + ray.dir * ray.tmin, ray.dir, t_end - ray.tmin,
                              throughput, rng, may_scatter, walk.local);
      } else {
        f = sample_free_flight(stack.mix(), t_end - ray.tmin, throughput, u.x, u.y, may_scatter);
        if (f.scattered) walk.local = stack.mix();
      }
      walk.emission += throughput * f.emission;
      throughput *= f.weight;
      if (f.scattered) {
        walk.scattered = true;
        walk.position = ray.origin + ray.dir * (ray.tmin + f.t);
        walk.distance = passed_length + ray.tmin + f.t;
        return walk;
      }
      walk.light_throughput = throughput;
      if (!(max_abs_component(throughput) > 0.0f)) {
        found = false;  // nothing comes back through this stretch
        walk.distance = passed_length + t_end;
        return walk;
      }
    }
    walk.distance = passed_length + t_end;
    if (!found || !media.pass_through(hit.material) || crossed >= kMaxBoundaries) return walk;
    stack.cross(media, hit.material, glm::dot(hit.geometric_normal, ray.dir) < 0.0f);
    passed_length += hit.t;
    ray.origin = offset_origin(hit.position, hit.geometric_normal, ray.dir);
    ray.tmax -= hit.t;
    ray.tmin = 0.0f;
    found = ray.tmax > 0.0f && scene.intersect(ray, hit);
  }
}

Vec3 media_shadow_transmittance(const Scene& scene, Ray ray, MediumStack stack, int max_transparent,
                                const PathState& receiver, float seed) {
  const SceneMedia& media = scene.media();
  Vec3 transmittance(1.0f);
  float travelled = 0.0f;
  for (int passed = 0, crossed = 0; crossed < kMaxBoundaries; ++crossed) {
    SurfaceHit hit;
    const bool found = ray.tmax > ray.tmin && scene.intersect(ray, hit);
    const float t_end = found ? hit.t : ray.tmax;
    if (stack.mix().varies()) {
      Rng rng = tracking_rng(seed, ray.origin.x + ray.dir.y, ray.origin.y + ray.origin.z + ray.dir.z);
      transmittance *= ratio_tracking(scene, stack.mix(), ray.origin + ray.dir * ray.tmin, ray.dir,
                                      std::max(t_end - ray.tmin, 0.0f), rng);
    } else if (stack.mix().extinguishes()) {
      transmittance *= torrance::transmittance(stack.mix().sigma_t(), std::max(t_end - ray.tmin, 0.0f));
    }
    if (!found || !(max_abs_component(transmittance) > 0.0f)) return transmittance;
    if (media.pass_through(hit.material)) {
      stack.cross(media, hit.material, glm::dot(hit.geometric_normal, ray.dir) < 0.0f);
    } else {
      if (!through_transparent_surface(scene, hit, ray.dir, receiver, passed, travelled, max_transparent,
                                       transmittance))
        return Vec3(0.0f);
      ++passed;
    }
    ray.origin = offset_origin(hit.position, hit.geometric_normal, ray.dir);
    ray.tmax -= hit.t;
    ray.tmin = 0.0f;
    travelled += hit.t;
  }
  return transmittance;
}

}  // namespace torrance
