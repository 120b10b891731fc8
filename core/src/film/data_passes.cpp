// The first-sample data passes (Depth, Position, Object Index, Material Index) as Cycles 3.4
// writes them (film_write_data_passes at sample 0): of the ray through the pixel's centre
// (Cycles' first sample takes the filter's centre), at the first surface whose alpha reaches the
// view layer's Alpha Threshold (surfaces below it are passed, as the transparent path would); 0
// on the world (Depth 1e10).
#include "film/film_passes.h"

namespace torrance {

void first_sample_data(const PathContext& ctx, Ray ray, PathRadiance& r) {
  r.depth = 1e10f;
  r.position = Vec3(0.0f);
  r.object_index = r.material_index = 0.0f;
  PathState state;
  state.ray_flags = kRayCamera;
  const float threshold = ctx.settings.pass_alpha_threshold;
  for (int passed = 0;; ++passed) {
    SurfaceHit hit;
    if (!ctx.scene.intersect(ray, hit)) return;
    // Cycles' camera_z_depth: along the camera's axis (panoramic: the distance from it).
    r.depth = ctx.depth_from ? glm::length(hit.position - *ctx.depth_from)
                             : glm::dot(hit.position - ctx.camera_position, ctx.camera_forward);
    r.position = hit.position;
    r.object_index = hit.object_settings.pass_index;
    r.material_index = ctx.scene.material_pass_index(hit.material);
    if (!(threshold > 0.0f) || passed >= ctx.settings.max_transparent_bounces) return;
    state.transparent_depth = uint8_t(std::min(passed, 255));
    if (ctx.scene.opacity(hit, ray.dir, state) >= threshold) return;
    ray.origin = offset_origin(hit.position, hit.geometric_normal, ray.dir);
    ray.tmax -= hit.t;
    ray.tmin = 0.0f;
    if (!(ray.tmax > 0.0f)) return;
  }
}

}  // namespace torrance
