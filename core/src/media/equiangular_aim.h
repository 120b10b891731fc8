// What a path's equiangular sampling aims at (media/equiangular.h, medium_walk.h's DirectAim): one
// point, spot or area light, chosen per ray by how much of it the ray can see, and the stretch of
// each ray where that light can shine at all (Cycles 4.x's valid ray segment: a spot's cone, the
// half-space in front of an area light), so that its equiangular points are not spent where it is
// dark.
//
// Any choice made before the walk's points are drawn keeps the estimate unbiased: given the light
// aimed at, distance and equiangular sampling are MIS-combined with that light's density along the
// stretch, whatever the NEE at each point then chooses. The reach only narrows that density where
// distance sampling covers the rest of the stretch (Multiple Importance); with Equiangular alone
// the whole stretch stays reachable, because the NEE at a point may choose another light.
#pragma once

#include "torrance/lights/lights.h"
#include "torrance/util/math.h"

#include <cstdint>

namespace torrance {

// Where along a line a light can shine: everywhere, inside a cone (a spot's, its apex moved back
// so that it holds the light's disk), or in front of a plane (an area light's).
struct LightReach {
  enum class Kind : uint8_t { Everywhere, Cone, Front };
  Kind kind = Kind::Everywhere;
  Vec3 apex{0.0f};  // the cone's apex, or a point of the plane
  Vec3 axis{0.0f};  // the cone's axis, or the plane's normal (towards where it shines); unit
  float cos_half = 0.0f;

  // Narrows [t0, t1] of origin + t dir (dir unit) to where the light can shine; false: nowhere.
  bool narrow(const Vec3& origin, const Vec3& dir, float& t0, float& t1) const;
};

struct AimTarget {
  Vec3 point{0.0f};  // the light's centre, where the equiangular density peaks
  LightReach reach;
};

// How many lights choose_aim chooses among (point, spot and area lights; 0: a path never aims, and
// draws no random numbers for it: a scene lit by suns alone renders as with distance sampling).
size_t aimable_lights(const Lights& lights);

// The light a ray's equiangular points aim at, chosen by u with probability proportional to its
// intensity times the angle the ray's reachable part [tmin, t_max] subtends at it over its
// distance to the ray (the integral of 1 / r^2 along that part); false when no light can shine on
// the ray (suns, the world and emitting meshes are left to distance sampling, as Cycles leaves
// distant lights).
bool choose_aim(const Lights& lights, const Vec3& origin, const Vec3& dir, float tmin, float t_max, float u,
                AimTarget& out);

}  // namespace torrance
