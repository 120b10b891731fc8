#include "integrator/shadow_catcher_split.h"

#include "scene/ray_queries.h"

namespace torrance {

PathContext catcher_half_context(const PathContext& ctx) {
  PathContext half = ctx;
  half.split_at_catchers = false;
  half.catcher_half = true;
  half.guide = nullptr;
  half.guide_training = false;
  half.roulette = nullptr;
  half.caustics = nullptr;
  half.mirror_images = nullptr;
  return half;
}

void trace_catcher_half(const PathContext& catcher_ctx, TraceFn trace, const Ray& camera_ray, SobolSampler sampler,
                        const PixelSample& pixel, PathRadiance& r) {
  struct CatchersOnly {  // this thread's rays see the catchers alone until the half is traced
    CatchersOnly() { ray_queries::set_mask(Scene::kCatcherOnlyMask); }
    ~CatchersOnly() { ray_queries::set_mask(0xFFFFFFFFu); }
  };
  PixelSample half_pixel = pixel;
  half_pixel.record = nullptr;
  half_pixel.start_media = r.catcher_media ? &*r.catcher_media : nullptr;  // (set by a path with media)
  Vec3 light;
  {
    CatchersOnly only;
    light = trace(catcher_ctx, camera_ray, sampler, nullptr, half_pixel).combined();
  }
  r.catcher.catcher = r.catcher.throughput * light;
  if (!catcher_ctx.settings.transparent_background) {
    PathState camera;
    camera.ray_flags = kRayCamera | kRayEmission;
    r.catcher.background = r.catcher.throughput * catcher_ctx.lights.world_radiance(camera_ray.dir, camera);
  }
}

}  // namespace torrance
