// Single scattering along the ray from the origin along +z through endless fog (the world's
// medium), as a path's walk estimates it (media/medium_walk.h): ∫ sigma_s T(t) direct(t) dt, with
// direct(p) the light arriving at p times the phase function, taken at the walk's equiangular
// points (aimed by aim.light_point and aim.reach) and at its scattering point. Mean and standard
// error over n walks (SobolSampler(seed, i, dimension)). For the equiangular tests.
#pragma once

#include "media/medium_walk.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace torrance::test {

struct Estimate {
  double mean = 0.0, std_error = 0.0;
};

using DirectAt = double (*)(const Vec3& p);

inline Estimate fog_single_scattering(const HomogeneousMedium& fog, DirectAim aim, DirectAt direct_at, int n,
                                      uint32_t seed, uint32_t dimension) {
  Scene scene;
  scene.set_world_volume(fog);
  scene.commit();
  struct Received {
    DirectAt direct_at;
    double sum = 0.0;
  } received{direct_at};
  aim.context = &received;
  aim.receive = [](void* context, const EquiangularPoint& p) {
    auto& r = *static_cast<Received*>(context);
    r.sum += double(p.weight.x) * r.direct_at(p.position);
  };
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    SobolSampler sampler(seed, uint32_t(i), dimension);
    Ray ray;
    ray.origin = Vec3(0.0f);
    ray.dir = Vec3(0.0f, 0.0f, 1.0f);
    ray.tmin = 0.0f;
    ray.tmax = std::numeric_limits<float>::infinity();
    SurfaceHit hit;
    bool found = false;
    MediumStack stack;
    stack.enter(scene.media(), scene.media().world());
    Vec3 throughput(1.0f);
    float passed = 0.0f;
    received.sum = 0.0;
    const MediumWalk walk = walk_media(scene, ray, hit, found, stack, throughput, sampler, true, passed, &aim);
    double x = received.sum;
    if (walk.scattered) x += double(throughput.x) * walk.direct_weight * direct_at(walk.position);
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(sum2 / n - mean * mean, 0.0) / n)};
}

}  // namespace torrance::test
