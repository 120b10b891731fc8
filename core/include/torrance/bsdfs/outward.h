// Directions turned over in the local shading frame (z = the normal): one implementation for
// the BSDFs whose frame has two sides (the glasses, the thin wall).
#pragma once

#include "torrance/util/math.h"

namespace torrance {

// A direction mirrored through the surface (z negated): a thin sheet's far side, or a frame
// turned over.
inline Vec3 mirror_z(const Vec3& w) { return Vec3(w.x, w.y, -w.z); }

// w in a glass's outward frame (z the outward normal) from the frame turned towards the viewer,
// which is the outward one turned over when backfacing; its own inverse.
inline Vec3 outward(const Vec3& w, bool backfacing) { return backfacing ? mirror_z(w) : w; }

}  // namespace torrance
