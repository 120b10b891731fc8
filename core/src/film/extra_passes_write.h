// What the path tracer writes into a sample's extra passes (extra_passes.h).
#pragma once

#include "torrance/film/extra_passes.h"
#include "torrance/util/math.h"
#include "torrance/integrator/path_state.h"

namespace torrance {

class Scene;
struct SurfaceHit;

// Adds the AOV Output nodes' inputs of the material at hit (seen along dir by a path in `state`)
// into a sample's extra channels; nothing for a material without them.
void add_aovs(const Scene& scene, const SurfaceHit& hit, const Vec3& dir, const PathState& state, float footprint,
              float* extras);

inline constexpr int kMaxLightGroups = kMaxExtraChannels / 3;

// Adds contribution c to light group `group`'s channels of a sample.
inline void add_to_light_group(const ExtraPasses& extra, int group, const Vec3& c, float* extras) {
  float* e = extras + extra.light_group_channel(group);
  e[0] += c.x;
  e[1] += c.y;
  e[2] += c.z;
}

// The light groups' parts of a contribution `total` (throughput x the lights' light, by_group
// each group's part of that light) which the path took as `arrived` (total, clamped: a scale).
inline void credit_split(const ExtraPasses& extra, const Vec3& total, const Vec3& arrived, const Vec3* by_group,
                         const Vec3& throughput, float* extras) {
  const int c = total.x >= total.y ? (total.x >= total.z ? 0 : 2) : (total.y >= total.z ? 1 : 2);
  if (!(total[c] > 0.0f)) return;
  const float kept = arrived[c] / total[c];
  for (int g = 0; g < extra.num_light_groups(); ++g)
    add_to_light_group(extra, g, throughput * by_group[g] * kept, extras);
}

}  // namespace torrance
