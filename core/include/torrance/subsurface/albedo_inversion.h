// From a subsurface closure's surface colour and radius to the volume the random walk travels
// through, as Cycles 3.4 does for Random Walk:
//
//  1. walk_radius (closure/bssrdf.h, bssrdf_setup_radius): the radius is scaled by
//     sqrt(3 (1 - a')), where a' is the reduced albedo whose dipole diffuse reflectance
//       Rd(a') = a'/2 (1 + exp(-4/3 A sqrt(3 (1 - a')))) exp(-sqrt(3 (1 - a')))
//     equals the colour (Jensen's dipole; A = (1 + F_dr) / (1 - F_dr) from the IOR's diffuse
//     Fresnel reflectance F_dr = -1.440/eta + 0.710/eta + 0.668 + 0.0636 eta), found by 12
//     bisection steps on [0, 1] (colour below 1e-4: a' = 0; from 0.995: a' = 0.999999).
//  2. walk_medium (integrator/subsurface_random_walk.h): Chiang, Kutz and Burley's fit (2016),
//     extended to anisotropy g by Wrenninge, Villemin and Hery, of the single-scattering
//     albedo whose walk reflects the colour; extinction sigma_t = 1 / (radius (1 - g)).
// Random Walk (Fixed Radius) skips step 1 and takes radius / (4 pi) (random_walk.cpp).
#pragma once

#include "torrance/util/math.h"

namespace torrance {

// Rd(a') of step 1 for the IOR's 4/3 A.
float dipole_reflectance(float reduced_albedo, float four_thirds_a);
// a' with dipole_reflectance(a') = colour (step 1).
float dipole_reduced_albedo(float colour, float four_thirds_a);
// The radius the walk uses (step 1), per channel.
Vec3 walk_radius(const Vec3& radius, const Vec3& colour, float ior);

struct WalkMedium {
  Vec3 sigma_t{0.0f};  // extinction (1/m)
  Vec3 alpha{0.0f};    // single-scattering albedo, in [0, 0.999999]
};
// Step 2, per channel: colour and the walk's radius (from walk_radius), anisotropy g in [0, 0.9].
WalkMedium walk_medium(const Vec3& colour, const Vec3& radius, float g);

}  // namespace torrance
