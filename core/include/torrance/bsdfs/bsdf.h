// The BSDF interface of Torrance.
//
// Conventions shared by every BSDF in the core:
//  * Directions are in the local shading frame (z = shading normal), unit length, and both point
//    AWAY from the surface: wo towards the viewer, wi towards the light.
//  * eval(wo, wi) returns f(wo, wi) * cos(theta_i): it INCLUDES the cosine foreshortening term,
//    so NEE computes L += throughput * eval * Le / pdf_light. eval_lobes() is the same value
//    split into its diffuse and glossy parts (eval = eval_lobes().total()).
//  * pdf(wo, wi) is the solid-angle density with which sample() produces wi (continuous lobes
//    only; a delta lobe has no density and is never returned by eval or pdf).
//  * sample() returns weight = eval / pdf for continuous lobes, and the delta lobe's weight
//    (its reflectance) for a delta direction.
//  * Reflection only: eval and pdf are 0 unless wo.z > 0 and wi.z > 0 -- except glass (glass.h),
//    whose frame's z is the outward normal and whose lobes also refract; MaterialBsdf combines
//    both (material_bsdf.h).
#pragma once

#include "torrance/bsdfs/thin_film.h"
#include "torrance/util/math.h"

namespace torrance {

// Which Cook-Torrance variant shades the scene.
enum class BrdfModel {
  Paper,         // exactly the brief's equations (GGX D, Schlick F, Schlick-GGX G, Lambert diffuse)
  Principled,    // Blender 3.4's Principled BSDF v1 as Cycles renders it (Burley, exact Fresnel, Smith G)
  PrincipledV2,  // Blender 4.x's Principled BSDF v2 as Cycles 4.x renders it (principled_v2.h)
};

// How Cycles' Principled v2 coat darkens the layers under it (principled_coat.h's CoatV2), per
// the Cycles generation that renders it.
enum class CoatLayering {
  Cycles4_2,  // 4.0-4.4 (4.2 checked): no energy compensation, albedo the smooth Fresnel F(cos)
  Cycles4_5,  // 4.5-5.0: compensated, albedo scale k mix(F0, 1, S) from the tables
  Cycles5_1,  // 5.1+ (5.3 checked): compensated lobe, per channel 1 - w (1 - tint (1 - A))
};

// A microfacet node's distribution (its `distribution`): GGX (also Multiscatter GGX, which
// multiscatter_ggx / multiscatter_walk tell), Beckmann (the Glass, Refraction, Glossy and Metallic
// nodes) or Ashikhmin-Shirley (the Glossy / Anisotropic node only: ashikhmin_shirley.h).
enum class MicrofacetDistribution { GGX, Beckmann, AshikhminShirley };

// The metallic/roughness material, as Blender's Principled BSDF names its inputs.
struct Material {
  Vec3 base_color{0.8f, 0.8f, 0.8f};
  float metallic = 0.0f;
  float roughness = 0.5f;
  float specular = 0.5f;  // dielectric F0 = 0.08 * specular (0.5 -> 0.04)
  float specular_tint = 0.0f;  // PRINCIPLED only: tints dielectric reflection towards the base hue
  Vec3 emission{0.0f};    // radiance emitted by both faces = emission colour * strength
  // PRINCIPLED_V2's Principled BSDF (Cycles 4.x): the emission lies under the coat and the sheen,
  // which darken (and tint) it as they do the layers under them, seen from the view
  // (PrincipledV2Bsdf::emission_weight). False: the emission as it is (every other closure, v1).
  bool emission_under_layers = false;
  // PRINCIPLED_V2 only (Blender 4.x's Principled inputs): the IOR input (with `specular` =
  // Specular IOR Level * F0(ior) / 0.04, so that F0 = 0.08 specular holds for every model), the
  // Specular Tint colour, and the node's distribution (Multiscatter GGX, or GGX when false; also
  // the Glossy BSDF's under PRINCIPLED_V2, glossy_bsdf.h).
  // The IOR input, also glass's (of the inside, > 0): Blender 3.4's default 1.45 (4.x: 1.5).
  float ior = 1.45f;
  Vec3 specular_tint_color{1.0f};
  bool multiscatter_ggx = true;
  // PRINCIPLED only: Blender 3.x's Multiscatter GGX, as Cycles 3.4 renders it: above roughness
  // 0.075 the specular lobe is the random walk of microsurface_walk.h with the lobe's Fresnel
  // (principled.h). Not with glass (transmission): that material renders GGX.
  bool multiscatter_walk = false;
  // Glass (glass.h): Principled Transmission (the share (1 - metallic) transmission of the
  // surface is glass: reflection untinted, refraction tinted by base_color, refraction roughness
  // 1 - (1 - roughness)(1 - transmission_roughness)), or Blender's Glass BSDF node (glass_node:
  // all glass, both lobes tinted by base_color, one roughness). ior: of the inside, > 0.
  float transmission = 0.0f;
  float transmission_roughness = 0.0f;
  bool glass_node = false;
  // The Glass, Refraction, Glossy or Metallic node's distribution (Ashikhmin-Shirley: the Glossy
  // closure's; the others read it as GGX).
  MicrofacetDistribution distribution = MicrofacetDistribution::GGX;
  bool beckmann() const { return distribution == MicrofacetDistribution::Beckmann; }
  // The Glass node as Cycles 4.0+ renders it (GGX, Multiscatter GGX, multiscatter_ggx telling
  // which, and Beckmann): one closure with the Fresnel per microfacet, both lobes tinted by its
  // Color (PrincipledGlassV2::glass_node); the Refraction node its refraction alone
  // (refraction_node). False: Cycles 3.4's pair of closures split by the Fresnel of the macro
  // normal (glass.h), or its random walk (multiscatter_walk); its Refraction closure.
  bool glass_cycles4 = false;
  // PRINCIPLED_V2's Thin Wall (Blender 5.x, thin_wall_v2.h): the surface is a thin sheet, its
  // transmission a slab seen alike from both sides and its subsurface a diffuse reflection and
  // translucency instead of a walk. Such a surface may send light through whatever its weights.
  bool thin_wall = false;
  // PRINCIPLED_V2's Diffuse Roughness (Blender 4.3+): above 0 the diffuse layer is the
  // energy-preserving Oren-Nayar of oren_nayar_eon.h (Cycles 4.3+), its albedo the base colour.
  float diffuse_roughness = 0.0f;
  bool transmits() const { return glass_node || thin_wall || (transmission > 0.0f && metallic < 1.0f); }
  // Transparency (the integrator, as Cycles' Transparent BSDF): with probability 1 - alpha a ray
  // goes straight through, tinted by transparent_color, and shadow rays are attenuated by
  // (1 - alpha) transparent_color. Principled Alpha: alpha, white; Transparent BSDF: alpha 0, its Color.
  float alpha = 1.0f;
  Vec3 transparent_color{1.0f};
  // The Principled BSDF's coat (principled_coat.h): v1's Clearcoat and Clearcoat Roughness
  // (PRINCIPLED; its IOR is fixed), v2's Coat Weight, Roughness, IOR and Tint (PRINCIPLED_V2).
  // A weight of 0 is no coat (and costs nothing).
  float coat_weight = 0.0f;
  float coat_roughness = 0.03f;
  float coat_ior = 1.5f;
  Vec3 coat_tint{1.0f};
  // v2's coat as which Cycles layers it (principled_coat.h's CoatV2): the add-on sets the running
  // Blender's.
  CoatLayering coat_layering = CoatLayering::Cycles4_5;
  // The Principled BSDF's sheen (principled_sheen.h): v1's Sheen and Sheen Tint (PRINCIPLED: the
  // tint a mix factor in [0, 1] towards the base colour's hue), v2's Sheen Weight, Roughness and
  // Tint colour (PRINCIPLED_V2). A weight of 0 is no sheen (and costs nothing).
  float sheen_weight = 0.0f;
  float sheen_roughness = 0.5f;
  float sheen_tint = 0.5f;
  Vec3 sheen_tint_color{1.0f};
  // Anisotropy (glossy_bsdf.h; the Glossy/Anisotropic BSDF node): in [-1, 1], the tangent's turn
  // about the normal in turns (Rotation) and the tangent (world; zero: none, isotropic).
  float anisotropy = 0.0f;
  float anisotropic_rotation = 0.0f;
  Vec3 tangent{0.0f};
  // Cycles 5.x: the transmission is stretched too: PRINCIPLED_V2's as its reflection (Anisotropic
  // in [0, 1]), the Glass node's by its own Anisotropy, Rotation and Tangent (the three fields
  // above, as the Glossy node's) (principled_glass_v2.h). False: isotropic, as Cycles 4.x.
  bool transmission_anisotropic = false;
  // Subsurface scattering (core/src/subsurface/, Cycles' Random Walk): v1's Subsurface factor
  // (PRINCIPLED: the diffuse lobe becomes the walk, its albedo base_color mixed towards
  // subsurface_color by it, its radius subsurface_radius times it) or the Subsurface Scattering
  // node's closure (ClosureType::Subsurface: base_color is its Color). subsurface_radius is the
  // per-channel mean free path in metres, Scale included. 0: no subsurface (and it costs nothing).
  float subsurface = 0.0f;
  Vec3 subsurface_radius{1.0f, 0.2f, 0.1f};
  Vec3 subsurface_color{0.8f};
  float subsurface_ior = 1.4f;
  float subsurface_anisotropy = 0.0f;
  // Cycles' "Random Walk (Fixed Radius)" (and Christensen-Burley, rendered so): the radius is
  // scaled by 1 / (4 pi) instead of being adjusted for the IOR and the colour.
  bool subsurface_fixed_radius = false;
  // Cycles 4.x's entry (the Subsurface Scattering node of Blender 4.x/5.x): a rough refraction of
  // GGX alpha subsurface_entry_alpha through subsurface_ior into the mesh (< 0: Cycles 3.4's
  // Lambertian entry); subsurface_skin: 4.x's Random Walk (Skin), half its entries Lambertian,
  // the others of alpha 1, its radius adjusted as 3.4's Random Walk.
  float subsurface_entry_alpha = -1.0f;
  bool subsurface_skin = false;
  // PRINCIPLED_V2 (Blender 4.x/5.x's Principled): `subsurface` is the Subsurface Weight, the walk
  // takes that share of the diffuse layer (its colour the base colour, its radius Radius x Scale,
  // its entry a rough refraction of alpha roughness^2 through the Principled's IOR; Skin: through
  // subsurface_ior), subsurface_lobe.h.
  // Cycles 4.0-4.4: channels whose radius is below this fraction of the ray's footprint at the hit
  // (Cycles' sd->dP) shade as diffuse instead of being walked (0.25; 0: only BSSRDF_MIN_RADIUS).
  float subsurface_min_footprint = 0.0f;
  // Cycles 5.x: walks go on after a diffuse bounce (4.x and 3.x shade them as diffuse there), and
  // Blender 5.3's Random Walk (subsurface_van_de_hulst): the radius is the mean free path as given
  // (no 1 / (4 pi), no IOR adjustment) and the single-scattering albedo is d'Eon's van de Hulst
  // mapping of the colour and the anisotropy (which may be negative), albedo_inversion.h.
  bool subsurface_after_diffuse = false;
  bool subsurface_van_de_hulst = false;
  // Christensen-Burley (any version): Cycles' disk sampling of Burley's profile instead of a walk
  // (subsurface/burley_disk.h); after a diffuse bounce it shades as diffuse in 5.x too.
  bool subsurface_burley = false;
  // Thin Film (thin_film.h; PRINCIPLED_V2's Principled BSDF of Blender 4.2+, and in 5.x the
  // Metallic and Glass BSDFs): Thickness in nm (<= 0.1: no film, the closures' plain Fresnel) and IOR;
  // thin_film_cycles5: Cycles 5.x's film (its table, the metal under a film too), else 4.x's.
  float thin_film_thickness = 0.0f;
  float thin_film_ior = 1.33f;
  bool thin_film_cycles5 = false;
  ThinFilm thin_film() const { return ThinFilm{thin_film_thickness, thin_film_ior, thin_film_cycles5}; }
  // PRINCIPLED_V2's Transmission Dispersion (Blender 5.x, dispersion.h): the inverse Abbe number
  // Scale / Abbe Number of its transmission (0: none; it costs nothing), and the wavelength (um)
  // of the path that shades it, which the integrator sets (0: the d line, no dispersion).
  float dispersion = 0.0f;
  float wavelength = 0.0f;
  // The Principled Hair BSDF's Offset (radians: the cuticle scales' tilt; ClosureType::PrincipledHair).
  float hair_offset = 0.0f;
  // Its Huang model's (ClosureType::PrincipledHairHuang) Aspect Ratio and the weights of its
  // Reflection, Transmission and Secondary Reflection paths.
  float hair_aspect_ratio = 1.0f;
  Vec3 hair_lobe_weights{1.0f};
  // Both models' per-strand randomness (hair/principled_hair_bsdf.h's HairRandomness): Random
  // Roughness, Random Color (0 and 0: base_color is the absorption at every hit), the Random
  // input (where the hit has no strand's own), and what the absorption is made of at each hit:
  // hair_coloring 0 Absorption Coefficient (base_color), 1 Melanin Concentration (hair_melanin,
  // hair_melanin_redness, hair_color = Tint), 2 Direct Coloring (hair_color = Color).
  float hair_random_roughness = 0.0f, hair_random_color = 0.0f, hair_random = 0.0f;
  int hair_coloring = 0;
  float hair_melanin = 0.0f, hair_melanin_redness = 0.0f;
  Vec3 hair_color{1.0f};
  // The Ray Portal BSDF's (ClosureType::RayPortal) Direction (world; zero: the ray's own) and,
  // where its Position is linked (portal_at_hit false), that position (world; else the hit's).
  Vec3 portal_direction{0.0f};
  Vec3 portal_position{0.0f};
  bool portal_at_hit = true;
};

// The normal a BSDF's diffuse lobes shade with, in its shading frame. The frame's z is the
// shading normal after valid_shading_normal (shading_normal.h): Cycles 3.4 checks every closure's
// normal so, Cycles 4.x (the PRINCIPLED_V2 model) only its specular, refracting, translucent
// and subsurface ones, so that its diffuse lobes (Diffuse BSDF, Principled's diffuse) keep the
// closure's normal as it came (`tilted`: it differs from z). A diffuse lobe then weighs a light
// direction wi by max(n.wi, 0) whatever side of n the viewer is on, as Cycles' do.
struct DiffuseNormal {
  Vec3 n{0.0f, 0.0f, 1.0f};
  bool tilted = false;
  float cosine(const Vec3& wi) const { return tilted ? glm::dot(n, wi) : wi.z; }
};

// The normal the Principled BSDF's coat shades with (principled_coat.h), in its shading frame:
// Cycles' Clearcoat / Coat Normal, which unlinked is the surface's normal without the Normal
// input's bump or normal map, checked as the specular closures' (coat_normal, shading_normal.h).
// `tilted`: it differs from z; the coat's eval, pdf and sample then work in `frame` about it.
// The same struct holds Principled v2's sheen normal (sheen_normal below): a frame tilted from z.
struct CoatNormal {
  Frame frame;
  bool tilted = false;
  // Both before the specular check, in the shading frame: the coat's normal and the closure's own
  // (the Normal input's). `leans`: they differ, and Cycles 4.x/5.x's Principled v2 sheen, whose
  // normal is the closure's leaned towards the coat's by the Coat Weight, tilts from z.
  Vec3 unchecked{0.0f, 0.0f, 1.0f};
  Vec3 closure{0.0f, 0.0f, 1.0f};
  bool leans = false;
  Vec3 to_coat(const Vec3& w) const { return tilted ? frame.to_local(w) : w; }
  float cosine(const Vec3& w) const { return tilted ? glm::dot(frame.n, w) : w.z; }
  Vec3 from_coat(const Vec3& w) const { return tilted ? frame.to_world(w) : w; }
  // Principled v2's sheen normal for a Coat Weight of coat_weight: normalize(mix(closure,
  // unchecked, clamp01(coat_weight))); not tilted unless `leans` (shading_normal.cpp).
  CoatNormal sheen_normal(float coat_weight) const;
};

// eval() split by lobe, for Blender's diffuse and glossy light passes.
struct LobeEval {
  Vec3 diffuse{0.0f};
  Vec3 glossy{0.0f};
  Vec3 total() const { return diffuse + glossy; }
};

struct BsdfSample {
  Vec3 wi{0.0f};
  Vec3 weight{0.0f};  // eval / pdf, or the delta lobe's reflectance
  float pdf = 0.0f;   // 0 for a delta lobe
  bool is_delta = false;
  bool diffuse = false;  // drawn from a diffuse lobe (Cycles' LABEL_DIFFUSE; the Light Path node)
  // The straight pass through a smooth thin wall (thin_wall_v2.h): Cycles 5.x's Transparent
  // closure for rays other than the camera's (the path tracer goes on as through alpha); and
  // Huang hair's pass outside its ellipse (huang_hair_bsdf.h), Cycles 4.x's Transparent closure.
  bool straight_through = false;
  bool valid() const { return pdf > 0.0f || is_delta; }
};

}  // namespace torrance
