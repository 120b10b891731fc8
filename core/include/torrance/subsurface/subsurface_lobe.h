// A surface's subsurface closure as Cycles 3.4 sets it up (closure/bssrdf.h, svm/closure.h): what
// the path tracer's choice of it weighs the path by, and what the random walk inside the mesh
// (random_walk.h) needs. Sampled instead of a BSDF direction with probability
// choice_probability(); never evaluated by next-event estimation (a BSSRDF has no eval in
// Cycles: its light arrives at the walk's exit, exit_bsdf.h).
//
//   Principled v1 (PRINCIPLED): weight (1 - metallic)(1 - transmission) x albedo, albedo = the
//     base colour mixed towards Subsurface Color by Subsurface, radius = Subsurface Radius x
//     Subsurface; the Principled's diffuse keeps only its retro-reflection (principled.cpp) and
//     the exit shades with Cycles' Lambert exit (1 - F_L / 2). IOR clamped to [1.01, 3.8],
//     anisotropy to [0, 0.9] (Cycles' clamps).
//   Subsurface Scattering node: weight = albedo = Color, radius = Radius x Scale, a plain
//     Lambertian exit; Blender 4.x's enters by a rough refraction (Material::subsurface_entry_alpha).
//   Principled v2 (PRINCIPLED_V2, Cycles 4.x/5.x's svm/closure.h): albedo = the base colour
//     clamped to 1, weight = albedo x Subsurface Weight x the diffuse layer's weight for the
//     view (what metallic, transmission, the dielectric's reflection, the coat and the sheen leave
//     it: PrincipledV2Bsdf::subsurface_weight, applied by MixtureBsdf::subsurface_weight once wo
//     is known), radius = Subsurface Radius x Scale, entry alpha = roughness^2 through the
//     Principled's IOR (as the Specular IOR Level sets it; Skin: through Subsurface IOR, alpha 1),
//     a plain Lambertian exit; the diffuse keeps 1 - Subsurface Weight (principled_v2.h).
// Channels whose radius is below min_walk_radius() are not walked: Cycles turns their weight
// into a diffuse lobe (lambert_channels(), walked_only()).
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

inline constexpr float kMinSubsurfaceRadius = 1e-8f;  // Cycles' BSSRDF_MIN_RADIUS

struct SubsurfaceLobe {
  Vec3 weight{0.0f};  // the closure's weight (mixture weight included), 0 in unwalked channels
  Vec3 albedo{0.0f};  // the surface colour the walk's single-scattering albedo is fitted to
  Vec3 radius{0.0f};  // per channel mean free path (m), before the IOR adjustment
  float ior = 1.4f;
  float anisotropy = 0.0f;
  bool fixed_radius = false;  // Material::subsurface_fixed_radius
  // Cycles 4.x's refractive entry's GGX alpha (< 0: 3.4's Lambertian entry) and whether half the
  // entries are Lambertian (Random Walk (Skin)).
  float entry_alpha = -1.0f;
  bool entry_half_lambertian = false;
  bool exit_fresnel = false;  // the exit shades with Cycles' Lambert exit (Principled), else Lambert
  // Blender 5.3's Random Walk (Material::subsurface_van_de_hulst): the radius as given
  // (plain_radius) and d'Eon's albedo mapping (van_de_hulst: also any negative anisotropy).
  bool plain_radius = false;
  bool van_de_hulst = false;
  bool burley = false;  // Christensen-Burley (Material::subsurface_burley): burley_disk.h, no walk
  // Principled v2: the index of its closure in the vertex's MixtureBsdf, whose layers scale
  // `weight` once the view is known (MixtureBsdf::subsurface_weight); -1: weight is final.
  int layered_component = -1;
  // How much of the vertex's sampling the other closures get, against the walk's Cycles sample
  // weight (its mean weight x its channel count): 0 where nothing else reflects.
  float others = 0.0f;

  bool active() const { return max_component(weight) > 0.0f; }
  // The probability that the path's continuation at the vertex is the walk.
  float choice_probability() const;
};

// Where the path is when it shades a hit, as Cycles' bssrdf_setup asks.
struct WalkState {
  bool walkable = true;           // false on hair strands and objectless hits: no walk, Lambert
  bool diffuse_ancestor = false;  // the path took a diffuse bounce (PATH_RAY_DIFFUSE_ANCESTOR)
  float footprint = 0.0f;         // the ray's footprint width at the hit (Cycles' sd->dP)
};
// The smallest radius material m's subsurface closure walks at state s (infinite: none):
// BSSRDF_MIN_RADIUS, Cycles 4.0-4.4's quarter footprint, none after a diffuse bounce but in 5.x.
float min_walk_radius(const Material& m, const WalkState& s);
// m with the subsurface radius of its channels below min_radius set to 0 (not walked: diffuse).
Material walked_only(const Material& m, float min_radius);

// The Principled v1 closure of material m (inactive without Subsurface or a diffuse lobe).
SubsurfaceLobe principled_subsurface(const Material& m, float mix_weight = 1.0f);
// The Principled v2 closure of material m (walked_only() already applied; eta: the IOR its
// dielectric layer refracts with, PrincipledV2Bsdf::dielectric_eta) as closure `component` of the
// vertex's mixture: its weight still without the layers (layered_component). Inactive without
// Subsurface Weight, a diffuse layer or a walked channel.
SubsurfaceLobe principled_v2_subsurface(const Material& m, float eta, int component, float mix_weight = 1.0f);
// The Subsurface Scattering node's closure (ClosureType::Subsurface) of material m.
SubsurfaceLobe node_subsurface(const Material& m, float mix_weight = 1.0f);
// Principled v1's channels that are not walked (radius below kMinSubsurfaceRadius): 1 there, 0
// elsewhere; all 1 without Subsurface.
Vec3 principled_lambert_channels(const Material& m);
// The colour Principled v1's diffuse lobe has under Subsurface (Cycles' mixed_ss_base_color).
Vec3 principled_subsurface_albedo(const Material& m);

}  // namespace torrance
