// Shading normals that never send reflections below the surface.
#pragma once

#include "torrance/math.h"

namespace torrance {

// Given the geometric normal ng facing wo (ng.wo > 0) and an interpolated shading normal ns
// (already on ng's side), returns a unit normal for which the mirror reflection of wo stays above
// the geometric surface: ng.R >= min(0.9 ng.wo, 0.01). Normals that fail are tilted towards ng,
// only as far as needed (found by bisection). Always finite; ng itself satisfies the bound.
Vec3 valid_shading_normal(const Vec3& ng, const Vec3& ns, const Vec3& wo);

}  // namespace torrance
