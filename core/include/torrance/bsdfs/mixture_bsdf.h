// A weighted sum of closures (Mix Shader / Add Shader), as Cycles combines a shader's closures:
//
//   eval(wo, wi) = sum_k w_k eval_k(wo, wi)
//   pdf(wo, wi)  = sum_k P_k pdf_k(wo, wi),   P_k = s_k / sum_j s_j,
//   s_k = w_k * (the closure's estimated albedo + 0.01)   (Cycles: the closure weight's average)
//   sample: choose closure k with probability P_k (by u_lobe, rescaled for the closure's own
//           lobe choice), sample it, then evaluate every closure at wi, so that weight =
//           eval / pdf of the whole mixture (one-sample MIS over closures). A closure's delta
//           lobe is returned as is, with weight w_k * its weight / P_k. A closure whose sample
//           is its own eval (kSampleIsOwnEval: the Hair BSDF's, Cycles' being inconsistent, and
//           3.x's Multiscatter GGX Glossy and Principled v1, whose pdf is an estimate)
//           counts with its sample's weight x pdf and pdf in place of its eval and pdf at wi, as
//           Cycles' surface_shader_bsdf_sample_closure counts the sampled closure.
//
// Components are MaterialBsdf (whatever the render's model is: it composes any future variant),
// DiffuseBsdf, GlossyBsdf, MultiscatterGlossyBsdf and the other nodes' closures (ClosureType); at most
// kMaxMixtureComponents, held by value (no allocation).
// See bsdf.h for the conventions.
#pragma once

#include "torrance/bsdfs/diffuse_bsdf.h"
#include "torrance/bsdfs/glossy_bsdf.h"
#include "torrance/bsdfs/metallic_bsdf.h"
#include "torrance/hair/hair_bsdf.h"
#include "torrance/hair/huang_hair_bsdf.h"
#include "torrance/hair/principled_hair_bsdf.h"
#include "torrance/bsdfs/material_bsdf.h"
#include "torrance/bsdfs/mixture.h"
#include "torrance/bsdfs/multiscatter_glossy_bsdf.h"
#include "torrance/bsdfs/refraction_bsdf.h"
#include "torrance/shader/shader_program.h"
#include "torrance/bsdfs/sheen_bsdf.h"
#include "torrance/bsdfs/toon_bsdf.h"
#include "torrance/bsdfs/translucent_bsdf.h"
#include "torrance/bsdfs/velvet_bsdf.h"
#include "torrance/subsurface/exit_bsdf.h"
#include "torrance/subsurface/subsurface_lobe.h"

#include <array>
#include <variant>

namespace torrance {

struct ClosureList;

class Scene;

class MixtureBsdf {
 public:
  using Component = std::variant<std::monostate, MaterialBsdf, DiffuseBsdf, GlossyBsdf, VelvetBsdf, SheenBsdf,
                                 TranslucentBsdf, RefractionBsdf, ToonBsdf, PrincipledHairBsdf, SubsurfaceExitBsdf,
                                 MetallicBsdf, HairBsdf, MultiscatterGlossyBsdf, HuangHairBsdf>;

  MixtureBsdf() = default;
  explicit MixtureBsdf(const MaterialBsdf& single) { add(single, 1.0f, 1.0f); }

  // Adds a closure with weight w (> 0) sampled in proportion to w * (sampling_albedo + 0.01).
  // Beyond kMaxMixtureComponents closures, std::length_error.
  void add(const Component& c, float w, float sampling_albedo);
  int size() const { return count_; }

  // The interface of MaterialBsdf (material_bsdf.h): `backfacing` goes to glass components;
  // kGlass is accepted for the integrator's sake and ignored (a mixture always checks for glass).
  template <bool kGlass = true>
  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi, bool backfacing = false) const {
    return eval_mixture(wo, wi, backfacing);
  }
  template <bool kGlass = true>
  Vec3 eval(const Vec3& wo, const Vec3& wi, bool backfacing = false) const {
    return eval_mixture(wo, wi, backfacing).total();
  }
  template <bool kGlass = true>
  float pdf(const Vec3& wo, const Vec3& wi, bool backfacing = false) const {
    return pdf_mixture(wo, wi, backfacing);
  }
  template <bool kGlass = true>
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u, bool backfacing = false) const {
    return sample_mixture(wo, u_lobe, u, backfacing);
  }
  // The density of the directions sample() draws: pdf() less the Refraction closures' pairs that
  // no microfacet connects, which they value as Cycles does but never draw (refraction_pair.h).
  // (A MaterialBsdf closure's glass counts whole: its own tests check its drawn pairs.)
  float pdf_drawn(const Vec3& wo, const Vec3& wi, bool backfacing = false) const {
    return pdf_mixture(wo, wi, backfacing, {}, {}, -1, true);
  }
  bool transmits() const;  // some closure is glass, Translucent, Refraction, Principled Hair (either model) or Hair
  // Every closure is a Hair BSDF's: Cycles' hair closures check no geometric side (the path
  // tracer then leaves out its check that the geometric and shading normals agree on wi's side).
  bool hair_only() const;
  // Whether a sample may pass the ray straight on as a transparent surface: a MaterialBsdf's
  // smooth thin wall, or an elliptical Huang hair closure on a curve (its hits outside the ellipse).
  bool passes_straight() const;
  // Its closures' world tangents into the shading frame (anisotropic glossy, hair); before at().
  void orient(const Frame& frame);
  // A Principled v2 subsurface lobe's weight for the view wo: its layered closure's
  // (subsurface_lobe.h: SubsurfaceLobe::layered_component) times that closure's mixture weight.
  void finish_subsurface(SubsurfaceLobe& lobe, const Vec3& wo) const;

  // The View interface of MaterialBsdf: a mixture prepares nothing (each closure its own wo);
  // `diffuse`, `coat`: its diffuse lobes' and its Principled coats' normals (bsdf.h).
  struct View {
    Vec3 wo{0.0f, 0.0f, 1.0f};
    bool backfacing = false;
    DiffuseNormal diffuse;
    CoatNormal coat;
  };
  View at(const Vec3& wo, bool backfacing = false, const DiffuseNormal& diffuse = {}, const CoatNormal& coat = {}) const {
    return View{wo, backfacing, diffuse, coat};
  }
  template <bool kGlass = true>
  LobeEval eval_lobes(const View& v, const Vec3& wi) const {
    return eval_mixture(v.wo, wi, v.backfacing, v.diffuse, v.coat);
  }
  template <bool kGlass = true>
  float pdf(const View& v, const Vec3& wi) const {
    return pdf_mixture(v.wo, wi, v.backfacing, v.diffuse, v.coat);
  }
  template <bool kGlass = true>
  BsdfSample sample(const View& v, float u_lobe, const Vec2& u) const {
    return sample_mixture(v.wo, u_lobe, u, v.backfacing, v.diffuse, v.coat);
  }
  Vec3 straight_through(const View& v) const;

  // Principled v2 closures' emission, which Cycles 4.x/5.x darkens by their coat and sheen seen
  // from the view (Material::emission_under_layers): shade_material keeps it here apart from the
  // resolved emission (weighted by the closure's mixture weight), layered_emission weighs it for
  // the view wo about the mixture's coat normal (each closure's sheen leaning by its Coat Weight).
  void add_layered_emission(const Material& m, const Vec3& weighted_emission);
  Vec3 layered_emission(const Vec3& wo, const CoatNormal& coat) const;

 private:
  // (skip: a closure left out of the sum, -1 none.)
  LobeEval eval_mixture(const Vec3& wo, const Vec3& wi, bool backfacing, const DiffuseNormal& diffuse = {},
                        const CoatNormal& coat = {}, int skip = -1) const;
  float pdf_mixture(const Vec3& wo, const Vec3& wi, bool backfacing, const DiffuseNormal& diffuse = {},
                    const CoatNormal& coat = {}, int skip = -1, bool drawn_only = false) const;
  // Whether closure c's sample counts as its own eval (kSampleIsOwnEval).
  static bool sample_is_own_eval(const Component& c);
  BsdfSample sample_mixture(const Vec3& wo, float u_lobe, const Vec2& u, bool backfacing,
                            const DiffuseNormal& diffuse = {}, const CoatNormal& coat = {}) const;

  std::array<Component, kMaxMixtureComponents> components_{};
  std::array<float, kMaxMixtureComponents> weights_{};
  std::array<float, kMaxMixtureComponents> probabilities_{};  // P_k, normalised after each add
  std::array<float, kMaxMixtureComponents> sampling_{};       // s_k
  int count_ = 0;
  struct LayeredEmission {
    Vec3 emission{0.0f};
    CoatV2 coat;
    SheenV2 sheen;
    float coat_weight = 0.0f;
  };
  std::array<LayeredEmission, kMaxMixtureComponents> layered_;
  int layered_count_ = 0;
};

// What the integrator shades with at a hit on material `id`: its BSDF (a single MaterialBsdf for
// an ordinary material, a mixture's closures otherwise) and, in `resolved`, the material's
// emission and an albedo (base_color, metallic 0 for mixtures) at the hit `globals` describe
// (textures and shader programs read when `textured`). `prebuilt` is the material's BSDF when
// untextured. program_regs (if given): where the material's program (a mixture's: its factors'
// and Normal's) leaves its registers, for Scene::normal_mapped at this hit. closures (if given):
// a mixture's closures with their weights, for the denoising features (denoising_features.h).
// subsurface (if given): where the material's first subsurface closure goes (Principled v1's
// Subsurface, v2's Subsurface Weight, a Subsurface Scattering node; subsurface_lobe.h), the path
// tracer walking it instead of a BSDF sample (a v2 lobe after finish_subsurface); without it a
// Subsurface Scattering node is a white Lambert of its Color. walk: where the path is; channels
// it does not walk (min_walk_radius: all after a diffuse bounce but in Cycles 5.x, Cycles 4.0-4.4's
// quarter footprint) shade as diffuse (Principled v1's Burley of the mixed colour, the node's and
// v2's Lambert). wavelength: the path's (um; 0: none), which dispersive closures refract with
// (dispersion.h); `resolved.wavelength` is it where one of the closures disperses, else 0.
MixtureBsdf shade_material(const Scene& scene, uint32_t id, const ShaderGlobals& globals, bool textured,
                           BrdfModel model, const MaterialBsdf& prebuilt, Material& resolved,
                           glm::vec4* program_regs = nullptr, ClosureList* closures = nullptr,
                           SubsurfaceLobe* subsurface = nullptr, const WalkState& walk = {},
                           float wavelength = 0.0f);

// The estimated albedo a mixture samples a Principled closure by: luminance of the base colour
// plus its dielectric F0.
float principled_sampling_albedo(const Material& m);

}  // namespace torrance
