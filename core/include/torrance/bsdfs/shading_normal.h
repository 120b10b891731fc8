// Shading normals that never send reflections below the surface.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/util/math.h"

namespace torrance {

// Given the geometric normal ng facing wo (ng.wo > 0) and an interpolated shading normal ns
// (already on ng's side), returns a unit normal for which the mirror reflection of wo stays above
// the geometric surface: ng.R >= min(0.9 ng.wo, 0.01). Normals that fail are tilted towards ng,
// only as far as needed (found by bisection). Always finite; ng itself satisfies the bound.
Vec3 valid_shading_normal(const Vec3& ng, const Vec3& ns, const Vec3& wo);

// The normal the diffuse lobes shade with (bsdf.h), in `frame`, whose z is `checked` =
// valid_shading_normal(ng, unchecked, wo): Cycles 3.4 checks every closure's normal (not tilted),
// Cycles 4.x (model PRINCIPLED_V2) only the specular ones, so its diffuse lobes keep `unchecked`.
DiffuseNormal diffuse_normal(const Frame& frame, const Vec3& checked, const Vec3& unchecked, BrdfModel model);

// The normal the Principled coat shades with (bsdf.h), in `frame`, whose z is `checked` (the
// closures' normal after valid_shading_normal): `coat` (the Coat Normal, or the surface's normal
// without the Normal input's bump; facing the viewer, as ng) made valid for wo as every specular
// closure's normal is (Cycles 3.4 and 4.x alike). Not tilted when that is `checked` itself.
// `closure`: the closures' normal before the check (for the sheen's, CoatNormal::sheen_normal).
CoatNormal coat_normal(const Frame& frame, const Vec3& checked, const Vec3& ng, const Vec3& coat, const Vec3& wo,
                       const Vec3& closure);

}  // namespace torrance
