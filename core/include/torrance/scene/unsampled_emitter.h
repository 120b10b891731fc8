// SurfaceHit::emitter of an emissive surface that no light samples: a point of an emissive
// material (Scene::add_points), as Cycles' emissive points, which are not in its light
// distribution. The paths that hit one take all of its emission (no MIS); -1 stays "emits
// nothing" and indices >= 0 the mesh light's triangles.
#pragma once

#include <cstdint>

namespace torrance {

constexpr int32_t kUnsampledEmitter = -2;

}  // namespace torrance
