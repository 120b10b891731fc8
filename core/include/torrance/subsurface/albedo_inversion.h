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
// Blender 5.3's Random Walk instead of step 2 (Cycles 5.3's subsurface_random_walk_remap): d'Eon's
// van de Hulst mapping ("A Hitchhiker's Guide to Multiple Scattering", eq. 53.7) of the colour c
// and anisotropy g (in [-0.99, 0.99]) to the single-scattering albedo
//   alpha = (1 - s^2) / (1 - g s^2),  s = 4.09712 + 4.20863 c - sqrt(9.59217 + 41.6808 c + 17.7126 c^2),
// clamped to [0, 0.999999]; extinction sigma_t = 1 / radius.
WalkMedium van_de_hulst_medium(const Vec3& colour, const Vec3& radius, float g);

}  // namespace torrance
