// Directional albedo a(wo) = integral of f(wo, wi) cos(theta_i) over the hemisphere, computed two
// independent ways: deterministic quadrature (over half-vectors, refined near the GGX peak) and
// Monte Carlo with the BSDF's own sampler. Their agreement tests sample(); their values are the
// white-furnace table of a model.
#pragma once

#include "torrance/bsdfs/material_bsdf.h"

namespace torrance {

// Quadrature in half-vector space, dwi = 4 (wo.h) dwh, with theta_h split at atan(8 alpha) so that
// both the specular peak and the wide diffuse lobe are resolved. Delta lobes are not included.
double directional_albedo_quadrature(const MaterialBsdf& bsdf, const Vec3& wo, float alpha, int n_theta = 384,
                                     int n_phi = 192);

// Mean sample weight over n samples (includes delta lobes).
double directional_albedo_sampled(const MaterialBsdf& bsdf, const Vec3& wo, int n, uint32_t seed = 0);

}  // namespace torrance
