// The path's state at a shading point (what Cycles' Light Path node reads).
#pragma once

#include <cstdint>

namespace torrance {

// The path's state where a program runs, as Cycles' path flags and bounce counts (what the Light
// Path node reads): the kRay* bits of the ray that found the point, the bounces before it
// (transparent passes apart), and the length of the ray's last segment. Next-event estimation
// reads an emitter with kRayEmission, a shadow ray a surface's alpha with kRayShadow (Cycles'
// PATH_RAY_EMISSION and PATH_RAY_SHADOW: both count as one bounce further for Ray Depth).
struct PathState {
  uint8_t ray_flags = 0;
  uint8_t ray_depth = 0, diffuse_depth = 0, glossy_depth = 0, transmission_depth = 0, transparent_depth = 0;
  uint8_t portal_depth = 0;  // Ray Portals passed (Cycles 5.x's portal_bounce)
  float ray_length = 0.0f;
};
// PathState::ray_flags (Cycles' PATH_RAY_*).
constexpr uint8_t kRayCamera = 1, kRayDiffuse = 2, kRayGlossy = 4, kRaySingular = 8, kRayReflect = 16,
                  kRayTransmit = 32, kRayShadow = 64, kRayEmission = 128;

}  // namespace torrance
