// A path's ray through its media (media/medium_stack.h), as Cycles' shade_volume follows a
// segment: free flight through each homogeneous stretch between the surfaces it meets, crossing
// volume-only boundaries (no bounce: Cycles' volume bounds), until it scatters or stops at a
// surface. And a shadow ray's transmittance through the same media.
#pragma once

#include "media/equiangular_aim.h"
#include "media/medium_stack.h"
#include "torrance/camera/camera.h"
#include "torrance/integrator/path_state.h"
#include "torrance/lights/light_linking.h"
#include "torrance/scene/scene.h"
#include "torrance/util/sampling.h"

namespace torrance {

// A scattering point drawn by equiangular sampling (media/equiangular.h) in one homogeneous
// stretch of a walk: where the direct light is to be estimated, and its weight (the path's
// throughput at the stretch's start x sigma_s T / pdf, its MIS weight against the free flight's
// point included).
struct EquiangularPoint {
  Vec3 position{0.0f};
  Vec3 weight{0.0f};
  const MediumStack* stack = nullptr;  // the media there
  MediumMix local;
};

// Where a walk's direct light aims (Cycles' light sampled ahead of the volume segment): a point of
// the chosen light, where along each stretch it can shine (media/equiangular_aim.h; used with
// Multiple Importance only), and what takes each equiangular point. nullptr: distance sampling only.
struct DirectAim {
  Vec3 light_point{0.0f};
  LightReach reach;
  void* context = nullptr;
  void (*receive)(void* context, const EquiangularPoint& point) = nullptr;
};

struct MediumWalk {
  bool scattered = false;
  Vec3 position{0.0f};  // where it scattered
  float distance = 0.0f;  // from the ray's origin (before the boundaries) to there, or to the surface
  Vec3 emission{0.0f};    // the media's emission reaching the ray's origin, throughput included
  // The throughput that lights met before `distance` are seen with (the scattering stretch's
  // free-flight weight left out; lights inside a chromatic medium: approximate).
  Vec3 light_throughput{1.0f};
  MediumMix local;  // the media's coefficients where it scattered (heterogeneous: at that point)
  // The weight of the direct light estimated where it scattered: 1 (distance sampling), 0 (the
  // stretch's direct light came from an equiangular point) or its MIS weight x 2 (Multiple
  // Importance, distance chosen).
  float direct_weight = 1.0f;
};

// Follows `ray` (tmin to the hit `hit`, if found) through `stack`'s media and the volume-only
// boundaries it meets: at each, the stack enters or leaves its medium, the ray moves on past it
// (its origin and tmax, passed_length growing by the stretch, as the alpha loop of trace_path does)
// and `hit`/`found` become the next surface's. throughput takes each free flight's weight.
// may_scatter false: past the path's last bounce (the media only absorb and emit).
// aim (may_scatter only): each homogeneous scattering stretch whose media's Volume Sampling is
// not Distance has its direct light's point drawn as that asks (equiangular toward
// aim->light_point, or one of the two, chosen with probability 1/2 each: Cycles' one-sample MIS,
// power heuristic); equiangular points go to aim->receive.
MediumWalk walk_media(const Scene& scene, Ray& ray, SurfaceHit& hit, bool& found, MediumStack& stack,
                      Vec3& throughput, SobolSampler& sampler, bool may_scatter, float& passed_length,
                      const DirectAim* aim = nullptr);

// The light a shadow ray (its origin to its tmax) carries through `stack`'s media: extinction
// along every stretch, volume-only boundaries crossed, other surfaces as trace_path's
// shadow_transmittance takes them (alpha < 1: (1 - alpha) x tint, at most max_transparent;
// opaque: 0).
// Heterogeneous media take ratio tracking, its random numbers from `seed` and the ray.
// A shadow-linked emitter's ray (shadow_sets: its blocker sets, light_linking.h) passes the
// surfaces that are none of its blockers as if absent, volume boundaries too (Cycles' shadow
// linking filter).
Vec3 media_shadow_transmittance(const Scene& scene, Ray ray, MediumStack stack, int max_transparent,
                                const PathState& receiver, float seed = 0.0f, uint64_t shadow_sets = kAllLinkSets);

}  // namespace torrance
