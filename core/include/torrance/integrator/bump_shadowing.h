// Light near the shadow terminator of bump- and normal-mapped surfaces, dimmed as the running
// Blender's Cycles dims it (RenderSettings::microfacet_bump_shadowing chooses the generation):
//
//  - Cycles 3.x and 4.x: Chiang, Li and Burley, "Taming the Shadow Terminator" (SIGGRAPH 2019
//    talk), a cubic in g, the ratio of the light's cosine to the smooth normal over the cosine it
//    would have were the mapped normal the surface's; on the diffuse lobes only.
//  - Cycles 5.x: Conty Estevez, Lecocq and Stein, "A Microfacet-Based Shadowing Function to Solve
//    the Bump Terminator Problem" (Ray Tracing Gems, 2019, ch. 12): the mapped normal is taken
//    for one microfacet of a GGX surface around the smooth normal whose roughness makes that
//    normal typical (alpha^2 = tan^2(theta_d) / 8, theta_d between the two normals, at most 1),
//    and the diffuse lobes are scaled by that surface's Smith masking G1 of the light. Besides,
//    light that the smooth normal and a lobe's normal put on different sides of the surface is
//    dropped: always for the diffuse lobes, for the other lobes where light is evaluated (a light
//    sample; a direction the BSDF drew keeps its glossy part).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/microfacet.h"
#include "torrance/util/math.h"

namespace torrance {

// Chiang et al.'s term (Cycles 3.x-4.x): n_smooth the interpolated normal, n_mapped the diffuse
// lobe's (bump- or normal-mapped) one, wi the light direction.
inline float bump_shadowing_chiang(Vec3 n_smooth, const Vec3& n_mapped, const Vec3& wi) {
  const float cos_mapped = glm::dot(n_mapped, wi);
  if (cos_mapped < 0.0f) n_smooth = -n_smooth;
  const float denom = cos_mapped * glm::dot(n_smooth, n_mapped);
  if (denom == 0.0f) return 1.0f;
  const float g = glm::dot(n_smooth, wi) / denom;
  if (g >= 1.0f) return 1.0f;
  if (g < 0.0f) return 0.0f;
  return g + g * g - g * g * g;
}

// Whether the smooth normal and a lobe's normal n_lobe put wi on the same side of the surface
// (Cycles 5.x; true where either is edge-on).
inline bool bump_sides_agree(const Vec3& n_smooth, const Vec3& n_lobe, const Vec3& wi) {
  return glm::dot(n_smooth, wi) * glm::dot(n_smooth, n_lobe) * glm::dot(n_lobe, wi) >= 0.0f;
}

// Conty Estevez et al.'s term (Cycles 5.x), in [0, 1]: 1 where the normals agree, 0 for light
// along or behind the smooth surface.
inline float bump_shadowing_microfacet(const Vec3& n_smooth, const Vec3& n_mapped, const Vec3& wi) {
  const float cos_d = std::abs(glm::dot(n_smooth, n_mapped));
  const float cos_i = std::abs(glm::dot(n_smooth, wi));
  if (cos_d >= 1.0f || cos_i >= 1.0f) return 1.0f;
  const float tan2_d = 1.0f / (cos_d * cos_d) - 1.0f;  // +inf for perpendicular normals
  const float alpha2 = std::min(0.125f * tan2_d, 1.0f);
  return ggx::smith_G1(cos_i, std::sqrt(alpha2));
}

// Dims the lobes f of light from wi at a mapped vertex: n_smooth its interpolated normal,
// n_diffuse and n_glossy the lobes' normals; evaluated: a light's sample (false: the BSDF's own).
inline void shadow_bumps(LobeEval& f, bool microfacet, const Vec3& n_smooth, const Vec3& n_diffuse,
                         const Vec3& n_glossy, const Vec3& wi, bool evaluated) {
  if (!microfacet) {
    f.diffuse *= bump_shadowing_chiang(n_smooth, n_diffuse, wi);
    return;
  }
  f.diffuse *= bump_sides_agree(n_smooth, n_diffuse, wi) ? bump_shadowing_microfacet(n_smooth, n_diffuse, wi) : 0.0f;
  if (evaluated && !bump_sides_agree(n_smooth, n_glossy, wi)) f.glossy = Vec3(0.0f);
}

}  // namespace torrance
