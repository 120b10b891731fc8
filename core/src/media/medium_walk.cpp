#include "media/medium_walk.h"

#include "integrator/shadow_rays.h"
#include "media/varying_tracking.h"

#include <algorithm>
#include <limits>

namespace torrance {

namespace {

constexpr int kMaxBoundaries = 1024;  // Cycles' VOLUME_BOUNDS_MAX

// The direct light's point of one homogeneous stretch [ray.tmin, t_end] whose free flight f has
// been drawn (throughput: the path's at the stretch's start): an equiangular point handed to aim,
// or the weight of the direct light at f's scattering point (walk.direct_weight).
void aim_direct_light(const DirectAim& aim, const Ray& ray, float t_end, const MediumStack& stack,
                      const Vec3& throughput, const FreeFlight& f, const glm::vec4& u, MediumWalk& walk) {
  const MediumMix& mix = stack.mix();
  const bool mis = mix.sampling() == VolumeSampling::MultipleImportance;
  // With MIS, equiangular points only where the light can shine (distance sampling covers the
  // rest); alone, the whole stretch (the NEE at a point may choose another light).
  float t0 = ray.tmin, t1 = t_end;
  if (mis && !aim.reach.narrow(ray.origin, ray.dir, t0, t1)) return;  // distance sampling alone (weight 1)
  const EquiangularSegment segment(ray.origin, ray.dir, aim.light_point, t0, t1);
  if (!segment.valid()) return;
  const bool equiangular = !mis || u.z >= 0.5f;
  if (!equiangular) {  // the free flight's point, weighed against equiangular's density there
    if (f.scattered)
      walk.direct_weight = 2.0f * power_heuristic(f.pdf, segment.pdf(ray.tmin + f.t));
    return;
  }
  if (f.scattered) walk.direct_weight = 0.0f;
  float pdf = 0.0f;
  const float t = segment.sample(u.w, pdf);
  if (!(pdf > 0.0f)) return;
  const float along = t - ray.tmin;
  EquiangularPoint point;
  point.weight = throughput * mix.sigma_s() * transmittance(mix.sigma_t(), along) / pdf;
  if (mis) point.weight *= 2.0f * power_heuristic(pdf, free_flight_pdf(mix, throughput, along));
  if (!(max_abs_component(point.weight) > 0.0f) || !is_finite(point.weight)) return;
  point.position = ray.origin + ray.dir * t;
  point.stack = &stack;
  point.local = mix;
  aim.receive(aim.context, point);
}

}  // namespace

MediumWalk walk_media(const Scene& scene, Ray& ray, SurfaceHit& hit, bool& found, MediumStack& stack,
                      Vec3& throughput, SobolSampler& sampler, bool may_scatter, float& passed_length,
                      const DirectAim* aim) {
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
        if (aim && may_scatter && stack.mix().scatters() && stack.mix().sampling() != VolumeSampling::Distance)
          aim_direct_light(*aim, ray, t_end, stack, throughput, f, u, walk);
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
                                const PathState& receiver, float seed, uint64_t shadow_sets) {
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
    if (!blocks_shadow(shadow_sets, hit.object_settings.blocker_set)) {
      // none of the shadow-linked emitter's blockers: passed as if absent
    } else if (media.pass_through(hit.material)) {
      stack.cross(media, hit.material, glm::dot(hit.geometric_normal, ray.dir) < 0.0f);
    } else if (!through_transparent_surface(scene, hit, ray.dir, receiver, passed++, travelled, max_transparent,
                                            transmittance)) {
      return Vec3(0.0f);
    }
    ray.origin = offset_origin(hit.position, hit.geometric_normal, ray.dir);
    ray.tmax -= hit.t;
    ray.tmin = 0.0f;
    travelled += hit.t;
  }
  return transmittance;
}

}  // namespace torrance
