// Precomputed GGX albedo tables for Principled v2 (principled_v2.h), laid out and interpolated as
// Cycles 4.x's own (so that Torrance reproduces its table-based terms, interpolation included),
// but computed here by Torrance's quadrature when first used (~0.2-0.5 s once per process):
//
//   E(r, mu)      directional albedo of single-scattering GGX (F = 1, alpha = r^2, height-correlated
//                 Smith G2) for a viewer at cos mu; 32 x 32 grid over r, mu in [0, 1].
//   E_avg(r)      its cosine-weighted hemispherical average, integral of 2 mu E(mu) dmu; 32 points.
//   S(r, mu, z)   the mean of the dielectric Fresnel interpolation factor
//                 s(wo.h) = clamp((F_dielectric(wo.h, eta) - F0) / (1 - F0), 0, 1) over the
//                 distribution of visible normals (zero where the reflected direction falls below
//                 the horizon), with z = ((eta - 1) / (eta + 1))^(1/2), i.e. eta = ior_from_F0(z^4);
//                 16 x 16 x 16 grid. The albedo of a GGX layer whose Fresnel is mix(f0, 1, s) is
//                 then estimated as mix(f0, 1, S).
//
// Grid point k of n sits at k / (n - 1), clamped to [1e-4, 1] for r and mu (to [1e-4, 0.99] for z);
// lookups clamp their arguments to [0, 1] and interpolate linearly. Each entry is an integral over
// the visible-normal parametrisation u in [0, 1]^2 (ggx::sample_visible_normal), by the midpoint
// rule on a regular grid: the table entry is E_u[w(u)] exactly as a sampled estimate would be.
#pragma once

#include <tbb/task_arena.h>

#include <memory>

namespace torrance::ggx_tables {

// Below this alpha Cycles 4.x treats GGX as a mirror (alpha_x alpha_y <= 5e-7).
inline constexpr float kDeltaAlpha = 7.0710678e-4f;

float albedo(float roughness, float mu);                             // E(r, mu)
float average_albedo(float roughness);                               // E_avg(r)
float dielectric_fresnel_mix(float roughness, float mu, float eta);  // S(r, mu, z(eta))
// The same interpolation factor for Schlick's Fresnel, the visible-normal mean of (1 - wo.h)^p,
// as Cycles 4.x reads its generalized-Schlick table for F82-tint metals (at z = 0.5, between its
// slices of exponents p = 5(1 - z)/z at z = 7/15 and 8/15, in equal parts): the metal's albedo
// estimate mix(f0, 1, S5).
float schlick_fresnel_mix(float roughness, float mu);  // S5(r, mu)

// The same integrals at one point, evaluated directly (no table), with an n x n grid over u:
// what the tables store at grid points; the tests use them to check table accuracy.
double albedo_direct(float roughness, float mu, int n);
double dielectric_fresnel_mix_direct(float roughness, float mu, float eta, int n);
double schlick_fresnel_mix_direct(float roughness, float mu, float exponent, int n);

// The Fresnel interpolation factor s(cos) for relative IOR eta (see above).
float dielectric_fresnel_factor(float cos_i, float eta);
// F0 of a dielectric with relative IOR eta, and the IOR with that F0 (f0 clamped to [0, 0.99]).
float f0_from_ior(float eta);
float ior_from_f0(float f0);

// Linear interpolation over a regular grid on [0, 1] (arguments clamped), as the tables above are
// read: n (nx, ny) points per axis, x the fastest; shared by the other tables (ggx_glass_tables.h).
float read_1d(const float* data, float x, int n);
float read_2d(const float* data, float x, float y, int nx, int ny);
float read_3d(const float* data, float x, float y, float z, int n);

// The tables of type T (built by T's constructor), made once per process, thread-safe. Isolated:
// while their parallel loops run, this thread must not pick up an outer task (e.g. another tile
// of the render that first asked for them), which would ask for them again inside their own
// initialisation.
template <typename T>
const T& built_once() {
  static const T t = [] {
    std::unique_ptr<T> made;
    tbb::this_task_arena::isolate([&] { made = std::make_unique<T>(); });
    return std::move(*made);
  }();
  return t;
}

}  // namespace torrance::ggx_tables
