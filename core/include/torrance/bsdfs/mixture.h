// Materials made of weighted closures, as Blender's Mix Shader and Add Shader build them.
//
// A Mixture lists its closures (components) and the Mix Shader factors at the hit. Each
// component's weight is the product of its path's terms through the shader tree, as Cycles'
// svm_node_mix_closure propagates them: the first (upper) shader of a Mix Shader gets 1 - fac,
// the second gets fac (fac clamped to [0, 1]); an Add Shader passes the weight on unchanged, so
// its two shaders simply add. A component's inputs live in an ordinary Scene material (with its
// image textures), read per closure type (see ClosureType).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/shader/texture.h"

#include <array>
#include <memory>
#include <vector>

namespace torrance {

inline constexpr int kMaxMixtureComponents = 8;
inline constexpr int kMaxMixFactors = 8;

// The Fac of one Mix Shader.
struct MixFactor {
  enum class Kind { Constant, Image, Checker, Program };
  Kind kind = Kind::Constant;
  float value = 0.5f;  // Constant
  int texture = -1;    // Image: the luminance of the texture's colour at the hit's UV
  // Checker (shader::checker, shader_textures.h) at (u, v, 0) * scale: the factor is color1 on
  // Color1's squares, color2 on the others (the Fac output: 1 and 0; the Color output: the colours'
  // luminances).
  float checker_scale = 5.0f;
  float checker_color1 = 1.0f, checker_color2 = 0.0f;
  int register_index = -1;  // Program: register x of the mixture's shader program
};

enum class ClosureType {
  Principled,  // the material as it is (the render's BRDF model)
  Diffuse,     // Diffuse BSDF: Color = base_color, Roughness = roughness (diffuse_bsdf.h)
  // Glossy BSDF (GGX, Beckmann or Ashikhmin-Shirley = distribution): Color = base_color, Roughness =
  // roughness (glossy_bsdf.h).
  Glossy,
  // Glossy BSDF of Blender 3.x with Multiscatter GGX: as Glossy, Cycles 3.4's random walk
  // (multiscatter_glossy_bsdf.h).
  GlossyMultiscatterV1,
  Emission,    // Emission: emission only
  // Transparent BSDF: rays pass straight through, tinted by the material's transparent_color.
  // Cycles' transparency: the mixture lets 1 - alpha through, alpha = 1 - the sum of these
  // closures' weights (clamped to [0, 1]); the path shades the other closures (their weights
  // divided by alpha) with probability alpha, so that their expectation is their weight.
  Transparent,
  Velvet,       // Velvet BSDF (3.x) / Sheen BSDF, Ashikhmin: Color = base_color, Sigma or Roughness = roughness
  Sheen,        // Sheen BSDF, Microfiber (4.x): Color = base_color, Roughness = roughness (sheen_bsdf.h)
  Translucent,  // Translucent BSDF: Color = base_color (translucent_bsdf.h)
  // Refraction BSDF: Color = base_color, Roughness = roughness, IOR = ior, Beckmann = beckmann(),
  // as Cycles 4.x/5.x = glass_cycles4 (refraction_bsdf.h).
  Refraction,
  // Toon BSDF (toon_bsdf.h): Color = base_color, Size = roughness, Smooth = transmission_roughness;
  // its directions sampled as Cycles 3.x samples them, or (the Cycles4 ones) as Cycles 4.x.
  ToonDiffuse,
  ToonGlossy,
  ToonDiffuseCycles4,
  ToonGlossyCycles4,
  // Holdout: no light of its own; for camera rays (through transparency) its weight times the
  // path's throughput is taken off the pixel's alpha (Cycles' holdout closure, Scene::holdout).
  Holdout,
  // Principled Hair BSDF (hair/principled_hair_bsdf.h): base_color = the absorption coefficient
  // (the add-on reduces the node's parametrisation to it), roughness = Roughness,
  // transmission_roughness = Radial Roughness, coat_weight = Coat, ior = IOR, hair_offset = Offset.
  PrincipledHair,
  // Its Huang model (Blender 4.0+; hair/huang_hair_bsdf.h): base_color = the absorption
  // coefficient, roughness = Roughness, ior = IOR, hair_offset = Offset, hair_aspect_ratio =
  // Aspect Ratio, hair_lobe_weights = Reflection, Transmission, Secondary Reflection.
  PrincipledHairHuang,
  // Subsurface Scattering node (core/src/subsurface/: Cycles' Random Walk): Color = base_color,
  // Radius x Scale = subsurface_radius, IOR = subsurface_ior, Anisotropy = subsurface_anisotropy.
  Subsurface,
  // Metallic BSDF (Blender 4.3+; metallic_bsdf.h), Roughness = roughness, Anisotropy, Rotation and
  // Tangent as the Glossy's fields, its distribution's Multiscatter GGX = multiscatter_ggx; F82 Tint:
  // Base Color = base_color, Edge Tint = specular_tint_color; Physical Conductor: IOR (n) =
  // specular_tint_color, Extinction (k) = sheen_tint_color.
  MetallicF82,
  MetallicConductor,
  // Diffuse BSDF of Blender 4.3+: as Diffuse, a Roughness above 0 the energy-preserving
  // Oren-Nayar (oren_nayar_eon.h) instead of Cycles 3.x-4.2's.
  DiffuseEnergyPreserving,
  // Hair BSDF node (hair/hair_bsdf.h), its Reflection or Transmission component: Color =
  // base_color, RoughnessU = roughness, RoughnessV = transmission_roughness, Offset = hair_offset,
  // a linked Tangent = tangent (world; zero: unlinked, the strand's or the triangle's direction).
  HairReflection,
  HairTransmission,
  // Ray Portal BSDF (Blender 4.2+; Cycles' ray portal): a ray that passes it by its weight (as a
  // Transparent closure's share, Scene::opacity) goes on from Position along Direction, tinted
  // by Color = base_color: Position = the program's portal_position register where linked (else
  // the hit point), Direction = portal_direction (world; zero: the ray's own). It stops shadow
  // rays; the light the ray meets after it is taken whole (no MIS: nothing sampled it).
  RayPortal,
};

struct MixtureComponent {
  ClosureType type = ClosureType::Principled;
  uint32_t material = 0;   // the Scene material holding the closure's inputs (not a mixture)
  std::vector<int> terms;  // weight = product of: t >= 0 -> factor t; t < 0 -> 1 - factor (-t - 1)
};

struct Mixture {
  std::vector<MixFactor> factors;
  std::vector<MixtureComponent> components;
  int program = -1;  // the shader program computing its Program factors (Scene::add_shader_program)
  bool transparent() const {
    for (const MixtureComponent& c : components)
      if (c.type == ClosureType::Transparent) return true;
    return false;
  }
  bool portal() const {
    for (const MixtureComponent& c : components)
      if (c.type == ClosureType::RayPortal) return true;
    return false;
  }
  // Whether some closure lets rays through (Transparent or Ray Portal).
  bool passes() const { return transparent() || portal(); }
  bool holdout() const {
    for (const MixtureComponent& c : components)
      if (c.type == ClosureType::Holdout) return true;
    return false;
  }
};

// Throws std::invalid_argument unless the mixture is well formed: 1..kMaxMixtureComponents
// components, at most kMaxMixFactors factors, finite constants, terms naming existing factors,
// texture ids below num_textures and component materials below num_materials.
void check_mixture(const Mixture& mixture, size_t num_materials, size_t num_textures);

// The components' weights at a hit (uv; image factors averaged over footprint UV units).
struct MixtureWeights {
  std::array<float, kMaxMixtureComponents> weight{};
  int count = 0;
};
// registers: the mixture's program's registers after running it (its Program factors read them;
// nullptr: they read 0).
MixtureWeights mixture_weights(const Mixture& mixture, const std::vector<std::shared_ptr<const Texture>>& textures,
                               const Vec2& uv, float footprint, const glm::vec4* registers = nullptr);

// Whether a closure of this type lets rays through instead of shading (Transparent, Ray Portal).
inline bool passes_rays(ClosureType t) { return t == ClosureType::Transparent || t == ClosureType::RayPortal; }
// The mixture's opacity at a hit from its weights there: 1 - its Transparent and Ray Portal
// closures' weights (clamped to [0, 1]; 1 without them).
float mixture_opacity(const Mixture& mixture, const MixtureWeights& w);
// The weights a path shades with once it has not passed through (Transparent and Ray Portal
// closures 0, the others divided by the opacity; unchanged without them).
void weights_when_opaque(const Mixture& mixture, MixtureWeights& w);

}  // namespace torrance
