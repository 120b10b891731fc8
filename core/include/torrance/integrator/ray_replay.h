// Raw Embree on the rays a render traced (ray_log.h): the same closest-hit and occlusion
// queries with nothing else around them (no shading, sampling or film), one by one or as
// coherent packets, to measure how much of Embree's speed the integrator keeps.
#pragma once

#include "torrance/integrator/integrator.h"
#include "torrance/integrator/ray_log.h"

#include <vector>

namespace torrance {

// The rays of a render of scene under settings (its image discarded), as RayLog logs them.
std::vector<LoggedRay> record_render_rays(Scene& scene, const RenderSettings& settings);

// The rays of one kind, in their order; unbounded_only keeps those with tmax = inf (shadow rays
// toward the sun or the world).
std::vector<LoggedRay> select_rays(const std::vector<LoggedRay>& rays, RayKind kind, bool unbounded_only = false);

// Traces the rays through the scene's BVH (committed: the scene has been rendered), writing each
// answer into its ray, in parallel over runs of consecutive rays on `threads` threads (0: all
// cores); returns the seconds it took. packet_width 1: rtcIntersect1 / rtcOccluded1 per ray;
// 8: consecutive rays of one kind go 8 at a time through rtcIntersect8 or rtcOccluded8 with the
// coherent flag (for coherent groups such as select_rays' camera rays).
double replay_rays(const Scene& scene, std::vector<LoggedRay>& rays, int packet_width = 1, int threads = 0);

}  // namespace torrance
