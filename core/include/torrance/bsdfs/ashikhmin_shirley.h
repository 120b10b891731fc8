// The Ashikhmin-Shirley reflection lobe (Ashikhmin & Shirley 2000, "An Anisotropic Phong BRDF
// Model"; Cycles' closure/bsdf_ashikhmin_shirley.h, the Glossy / Anisotropic BSDF node's
// Ashikhmin-Shirley distribution) in the lobe's frame (z = normal, x along the tangent): the
// paper's specular term without its Fresnel factor (a colour multiplies it, as every Cycles
// microfacet closure without Fresnel).
//
// Each alpha (Roughness^2, stretched by the Anisotropy as for GGX) is clamped to [1e-4, 1] and
// turned into a Phong exponent n = 2 / alpha^2 - 2 (n_x along x, n_y along y). Half vectors h are
// distributed over solid angle as
//
//   p_h(h) = sqrt((n_x + 1)(n_y + 1)) / (2 pi) (h.z)^e,   e = (n_x h.x^2 + n_y h.y^2) / (1 - h.z^2)
//
// (isotropic: (n + 1) / (2 pi) (h.z)^n), and with wo the view, wi the light, h = normalize(wo + wi):
//
//   f cos = wi.z p_h(h) / (4 (h.wo) max(wo.z, wi.z)),   pdf(wi) = p_h(h) / (4 h.wo)
//
// (Cycles' floors of 1e-6 on h.wo, h.z and the denominator kept). Sampling draws h from p_h
// exactly (isotropic: phi uniform, cos theta = u^(1 / (n + 1)); anisotropic: the paper's
// phi = atan(sqrt((n_x + 1) / (n_y + 1)) tan(pi u / 2)) per quadrant, cos theta = u^(1 / (e + 1)))
// and reflects wo about it. Since wi.z / max(wo.z, wi.z) <= 1 and pdf integrates to at most 1, a
// white lobe keeps at most the energy it receives. Both alphas at most 1e-4: a mirror (is_mirror;
// Cycles' singular sample of weight 1), no continuous part.
#pragma once

#include "torrance/util/math.h"

namespace torrance::ashikhmin_shirley {

inline constexpr float kMinAlpha = 1e-4f;

// The Phong exponent of an alpha (clamped to [kMinAlpha, 1] first, as Cycles' setup).
float exponent(float alpha);

// A mirror: both alphas at most kMinAlpha.
inline bool is_mirror(float alpha_x, float alpha_y) { return std::max(alpha_x, alpha_y) <= kMinAlpha; }

// p_h(h) above (0 for h.z <= 0; h.z floored at 1e-6 otherwise).
float half_vector_pdf(const Vec3& h, float alpha_x, float alpha_y);

// f cos and the density of wi (0 unless wo.z > 0 and wi.z > 0 and the lobe is no mirror).
float eval(const Vec3& wo, const Vec3& wi, float alpha_x, float alpha_y);
float pdf(const Vec3& wo, const Vec3& wi, float alpha_x, float alpha_y);

// A half vector drawn from p_h (h.z >= 0), and wo reflected about it (below the surface when the
// half vector faces away from wo).
Vec3 sample_half_vector(float alpha_x, float alpha_y, const Vec2& u);
Vec3 sample(const Vec3& wo, float alpha_x, float alpha_y, const Vec2& u);

}  // namespace torrance::ashikhmin_shirley
