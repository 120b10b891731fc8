// A strand's direction for the hair closures (principled_hair_bsdf.h, hair_bsdf.h): given in world
// space (a mixture's closures are made before the shading frame is known), turned into it.
#pragma once

#include "torrance/util/math.h"

namespace torrance {

// The unit direction of world vector `world` in `frame`; the frame's x where it has none.
inline Vec3 strand_in_frame(const Frame& frame, const Vec3& world) {
  const Vec3 local = frame.to_local(world);
  const float len = glm::length(local);
  return len > 0.0f && std::isfinite(len) ? local / len : Vec3(1.0f, 0.0f, 0.0f);
}

}  // namespace torrance
