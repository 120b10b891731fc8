#include "torrance/shader/shader_raycast.h"

#include <cmath>

namespace torrance::shader {

namespace {

// Where the ray starts (tmin) and which triangle it passes by, as Cycles' svm_raycast decides.
struct RayStart {
  float tmin = 0.0f;
  uint32_t skip_object = ShaderGlobals::kNoObject, skip_prim = 0;
};

RayStart ray_start(const ShaderGlobals& g, const Vec3& position, float bump_width) {
  RayStart s;
  if (bump_width > 0.0f) {
    const float differential = 0.5f * (glm::length(g.dpdx) + glm::length(g.dpdy));  // Cycles' sd->dP
    s.tmin = 1.1f * bump_width * differential;
  } else if (position == g.position) {
    s.skip_object = g.object;
    s.skip_prim = g.prim;
  }
  return s;
}

}  // namespace

OpValue raycast_op(const ShaderOpContext& c) {
  const ShaderGlobals& g = c.globals;
  const Vec3 position = c.vector(0), direction = c.vector(1);
  const float length = c.value(2);
  RaycastHit hit;
  bool found = false;
  // Cycles traces from an object's surface (a mesh's or a strand's), not from a world or light.
  const bool on_object = g.object != ShaderGlobals::kNoObject || g.on_curve;
  if (g.tracer && on_object && length > 0.0f) {
    const RayStart s = ray_start(g, position, c.value(3));
    const bool only_local = c.ins.flags & kRaycastOnlyLocal;
    if (!only_local || g.object != ShaderGlobals::kNoObject)
      found = g.tracer->raycast(position, direction, s.tmin, length, only_local ? g.object : ShaderGlobals::kNoObject,
                                s.skip_object, s.skip_prim, hit);
  }
  switch (c.ins.mode) {
    case 0: {
      if (!found) return glm::vec4(0.0f, 0.0f, length, 0.0f);
      const bool self = g.object != ShaderGlobals::kNoObject && hit.object == g.object;
      return glm::vec4(1.0f, self ? 1.0f : 0.0f, hit.t, 0.0f);
    }
    case 1: return found ? glm::vec4(position + direction * hit.t, 0.0f) : glm::vec4(0.0f);
    default: return found ? glm::vec4(hit.normal, 0.0f) : glm::vec4(0.0f);
  }
}

}  // namespace torrance::shader
