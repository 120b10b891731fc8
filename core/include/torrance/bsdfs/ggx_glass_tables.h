// The albedo of GGX glass for Principled v2's transmission (principled_glass_v2.h), laid out and
// read as Cycles 4.x's ggx_glass_E / ggx_glass_Eavg tables (and their _inv_ pair for a relative
// IOR below 1), computed here by Torrance's quadrature when first used:
//
//   E(r, mu, z)   directional albedo of single-scattering GGX glass with the exact dielectric
//                 Fresnel per microfacet (reflection F, refraction 1 - F; height-correlated Smith
//                 G2; a direction that leaves on the wrong side of the macro surface is lost), for
//                 a viewer at cos mu, alpha = r^2, relative IOR eta = ior_from_f0(z^4) (> 1) or its
//                 inverse (the _inv_ table); 16 x 16 x 16 points. At |eta - 1| < 1e-4 (z's first
//                 point) the refraction passes straight, unshadowed (Cycles' singular case): E = 1.
//   E_avg(r, z)   its cosine-weighted average, integral of 2 mu E(mu) dmu; 16 x 16 points.
//
// Grid and interpolation as ggx_tables.h (r, mu clamped to [1e-4, 1], z to [1e-4, 0.99]); a
// lookup's z = sqrt(|eta - 1| / (eta + 1)) of the IOR turned above 1. Each entry is the mean of
// G2 / G1(wo) over the visible normals (reflection with probability F, else refraction), by the
// midpoint rule on a regular u grid crowded towards the rare steep normals.
#pragma once

namespace torrance::ggx_glass_tables {

float albedo(float roughness, float mu, float eta);   // E, from the table for eta's side
float average_albedo(float roughness, float eta);     // E_avg, likewise

// The same integral at one point without the table (n x n grid over u): the tests' reference.
double albedo_direct(float roughness, float mu, float eta, int n);

}  // namespace torrance::ggx_glass_tables
