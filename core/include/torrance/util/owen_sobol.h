// Points of a 2-D Owen-scrambled Sobol sequence (its first two dimensions, sampling.cpp's
// matrices and scramble), for sample sets drawn outside the path's sampler (shader ops that
// trace several rays from a hit: shader/hit_lattice.h).
#pragma once

#include "torrance/util/math.h"

#include <cstdint>

namespace torrance {

// Point `index` of the sequence scrambled by `seed`, in [0, 1)^2. Any aligned power-of-two run of
// indices (0 .. 2^m - 1 among them) is a (0, m, 2)-net: one point in every elementary interval of
// area 2^-m, uniformly placed within it, as a run of Cycles' PMJ02 points.
Vec2 owen_sobol_2d(uint32_t index, uint32_t seed);

}  // namespace torrance
