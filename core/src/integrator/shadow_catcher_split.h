// The catcher-only half of a camera path split at a shadow catcher (film/shadow_catcher.h):
// Cycles' PATH_RAY_SHADOW_CATCHER_PASS state, traced by the integrator after the path itself.
#pragma once

#include "integrator/path_tracer.h"

namespace torrance {

// The render's context for the catcher-only half: no further split, and nothing that learns from
// or stands in for the full scene's paths (guiding, the learned roulette, caustics by light
// tracing, mirror images).
PathContext catcher_half_context(const PathContext& ctx);

// The half of r's split path that sees only the catchers (Embree's mask: Scene::kCatcherOnlyMask,
// for its rays and its shadow rays alike): traced again from the camera ray, from the same
// random numbers as r's path (sampler: a copy taken before r's path drew any), its light times
// r's throughput at the split into r.catcher.catcher; with an opaque film the world along the
// camera ray into r.catcher.background (Cycles' PATH_RAY_SHADOW_CATCHER_BACKGROUND).
void trace_catcher_half(const PathContext& catcher_ctx, TraceFn trace, const Ray& camera_ray, SobolSampler sampler,
                        const PixelSample& pixel, PathRadiance& r);

}  // namespace torrance
