// A path's scattering vertex in a medium (Cycles' integrate_volume_direct_light and
// integrate_volume_phase_scatter): next-event estimation of one light with the phase function,
// MIS-weighted (power heuristic) against phase sampling, its shadow ray through the media; then
// the phase function sampled for the path's next direction (its weight is 1: exact sampling). The
// direct light's point may be another one than the path's (equiangular sampling: medium_walk.h).
#pragma once

#include "media/medium_walk.h"
#include "torrance/lights/light_choice.h"

namespace torrance {

struct MediumNextEvent {
  Vec3 light{0.0f};  // arriving x phase x MIS / choice probability (the path's throughput not included)
  size_t light_index = 0;
  LightSample sample;  // for the light's group
};

// NEE at p inside `stack`'s media, the path having arrived travelling along -wo. The light is chosen
// as at a two-sided surface whose normal is the path's direction (choice keeps the
// probabilities, for the MIS of a light the phase-sampled ray meets); u: choice, position on the light.
// at: the media's coefficients at p (its phase function); u.w seeds heterogeneous media's tracking.
// weight: the point's share of the direct light (MediumWalk::direct_weight); 0: the choice is
// made (for the phase-sampled ray's MIS) but no light sampled.
MediumNextEvent medium_next_event(const Scene& scene, const Vec3& p, const Vec3& wo, const MediumStack& stack,
                                  const MediumMix& at, LightChoice& choice, const glm::vec4& u, const PathState& state,
                                  int max_transparent, float weight = 1.0f);

}  // namespace torrance
