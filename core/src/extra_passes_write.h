// What the path tracer writes into a sample's extra passes (extra_passes.h).
#pragma once

#include "torrance/extra_passes.h"
#include "torrance/math.h"
#include "torrance/path_state.h"

namespace torrance {

class Scene;
struct SurfaceHit;

// Adds the AOV Output nodes' inputs of the material at hit (seen along dir by a path in `state`)
// into a sample's extra channels; nothing for a material without them.
void add_aovs(const Scene& scene, const SurfaceHit& hit, const Vec3& dir, const PathState& state, float footprint,
              float* extras);

}  // namespace torrance
