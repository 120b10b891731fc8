#include "media/medium_vertex.h"

#include <algorithm>

namespace torrance {

MediumNextEvent medium_next_event(const Scene& scene, const Vec3& p, const Vec3& wo, const MediumStack& stack,
                                  const MediumMix& at, LightChoice& choice, const glm::vec4& u, const PathState& state,
                                  int max_transparent, float weight) {
  MediumNextEvent out;
  const Lights& lights = scene.lights();
  const Vec3 n = -wo;
  choice.score(lights, p, n, true, false, [](const Vec3&) { return 0.0f; });
  const Lights::Choice chosen = choice.select(u.x);
  if (!(chosen.probability > 0.0f) || weight == 0.0f) return out;
  out.light_index = chosen.index;
  const LightSample ls = lights.sample(chosen.index, p, n, Vec2(u.y, u.z), true, state);
  if (!ls.valid()) return out;
  // Light linking (light_linking.h): a medium's receiver set is the default; a shadow-linked
  // emitter's shadow ray passes its non-blockers.
  uint64_t shadow_sets = kAllLinkSets;
  if (const LightLinks& links = lights.links(); links.any()) {
    const uint8_t entry = lights.link_entry(chosen.index, ls);
    if (!links.lights(entry, 0)) return out;
    shadow_sets = links.shadow_sets(entry);
  }
  const bool shadow_linked = shadow_sets != kAllLinkSets;
  const float phase = at.phase_pdf(wo, ls.wi);
  if (!(phase > 0.0f)) return out;
  Ray ray;
  ray.origin = p;
  ray.dir = ls.wi;
  ray.tmin = 0.0f;
  ray.tmax = std::isinf(ls.distance) ? ls.distance : ls.distance * (1.0f - 1e-4f);
  const Vec3 transmittance = media_shadow_transmittance(scene, ray, stack, max_transparent, state, u.w, shadow_sets);
  if (!(max_abs_component(transmittance) > 0.0f)) return out;
  const float mis = ls.pdf > 0.0f && !shadow_linked ? power_heuristic(chosen.probability * ls.pdf, phase) : 1.0f;
  out.light = ls.weight * transmittance * (phase * mis * weight / chosen.probability);
  out.sample = ls;
  return out;
}

}  // namespace torrance
