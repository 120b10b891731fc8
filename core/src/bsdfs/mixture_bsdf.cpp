#include "torrance/bsdfs/mixture_bsdf.h"

#include "film/denoising_features.h"
#include "hair/hair_closures.h"

#include "torrance/scene/scene.h"

#include <limits>
#include <stdexcept>

namespace torrance {
namespace {

// The frame of a DiffuseBsdf closure: about the diffuse normal d (bsdf.h) where it is tilted,
// else the shading frame itself.
struct DiffuseFrame {
  explicit DiffuseFrame(const DiffuseNormal& d) : tilted(d.tilted), frame(d.tilted ? Frame(d.n) : Frame()) {}
  Vec3 to_local(const Vec3& v) const { return tilted ? frame.to_local(v) : v; }
  Vec3 to_world(const Vec3& v) const { return tilted ? frame.to_world(v) : v; }
  bool tilted;
  Frame frame;
};

template <typename B, typename T>
constexpr bool is = std::is_same_v<std::decay_t<B>, T>;

// Whether a closure type declares kSampleIsOwnEval true (hair_bsdf.h).
template <typename T, typename = void>
struct SampleIsOwnEval : std::false_type {};
template <typename T>
struct SampleIsOwnEval<T, std::void_t<decltype(T::kSampleIsOwnEval)>> : std::bool_constant<T::kSampleIsOwnEval> {};

// Adds a closure sampled by its own estimate of its albedo.
template <typename Closure>
void add_closure(MixtureBsdf& bsdf, const Closure& closure, float weight) {
  bsdf.add(closure, weight, closure.sampling_albedo());
}

// Principled v1 as Cycles shades it after a diffuse bounce: its Subsurface becomes the full
// diffuse lobe of the mixed colour.
Material principled_as_diffuse(const Material& m) {
  Material d = m;
  d.base_color = principled_subsurface_albedo(m);
  d.subsurface = 0.0f;
  return d;
}

}  // namespace

float principled_sampling_albedo(const Material& m) {
  return luminance(glm::clamp(m.base_color, Vec3(0.0f), Vec3(1.0f))) +
         0.08f * std::max(m.specular, 0.0f) * (1.0f - clamp01(m.metallic));
}

void MixtureBsdf::add(const Component& c, float w, float sampling_albedo) {
  if (count_ >= kMaxMixtureComponents) throw std::length_error("a mixture holds at most 8 closures");
  if (!(w > 0.0f) || std::holds_alternative<std::monostate>(c)) return;
  components_[count_] = c;
  weights_[count_] = w;
  sampling_[count_] = w * (std::max(sampling_albedo, 0.0f) + 0.01f);
  ++count_;
  float sum = 0.0f;
  for (int k = 0; k < count_; ++k) sum += sampling_[k];
  for (int k = 0; k < count_; ++k) probabilities_[k] = sampling_[k] / sum;
}

void MixtureBsdf::add_layered_emission(const Material& m, const Vec3& weighted_emission) {
  if (layered_count_ >= kMaxMixtureComponents) return;
  LayeredEmission& e = layered_[layered_count_++];
  e.emission = weighted_emission;
  e.coat = m.coat_weight > 0.0f ? CoatV2(m) : CoatV2();
  e.sheen = m.sheen_weight > 0.0f ? SheenV2(m.sheen_weight, m.sheen_roughness, m.sheen_tint_color) : SheenV2();
  e.coat_weight = m.coat_weight;
}

Vec3 MixtureBsdf::layered_emission(const Vec3& wo, const CoatNormal& coat) const {
  Vec3 sum(0.0f);
  for (int k = 0; k < layered_count_; ++k) {
    const LayeredEmission& e = layered_[k];
    sum += e.emission * PrincipledV2Bsdf::emission_weight(e.coat, e.sheen, coat.cosine(wo),
                                                          coat.sheen_normal(e.coat_weight).cosine(wo));
  }
  return sum;
}

LobeEval MixtureBsdf::eval_mixture(const Vec3& wo, const Vec3& wi, bool backfacing, const DiffuseNormal& diffuse,
                                   const CoatNormal& coat, int skip) const {
  const DiffuseFrame d(diffuse);
  LobeEval total;
  for (int k = 0; k < count_; ++k) {
    if (k == skip) continue;
    const LobeEval f = std::visit(
        [&](const auto& b) -> LobeEval {
          if constexpr (is<decltype(b), std::monostate>) return {};
          else if constexpr (is<decltype(b), MaterialBsdf>)
            return b.eval_lobes(b.at(wo, backfacing, false, diffuse, coat), wi);
          else if constexpr (is<decltype(b), DiffuseBsdf>) return b.eval_lobes(d.to_local(wo), d.to_local(wi));
          else if constexpr (is<decltype(b), RefractionBsdf>) return b.eval_lobes(wo, wi, backfacing);
          else return b.eval_lobes(wo, wi);
        },
        components_[k]);
    total.diffuse += weights_[k] * f.diffuse;
    total.glossy += weights_[k] * f.glossy;
  }
  return total;
}

float MixtureBsdf::pdf_mixture(const Vec3& wo, const Vec3& wi, bool backfacing, const DiffuseNormal& diffuse,
                               const CoatNormal& coat, int skip, bool drawn_only) const {
  const DiffuseFrame d(diffuse);
  float p = 0.0f;
  for (int k = 0; k < count_; ++k)
    if (k != skip) p += probabilities_[k] * std::visit(
                                 [&](const auto& b) -> float {
                                   if constexpr (is<decltype(b), std::monostate>) return 0.0f;
                                   else if constexpr (is<decltype(b), MaterialBsdf>)
                                     return b.pdf(b.at(wo, backfacing, true, diffuse, coat), wi);
                                   else if constexpr (is<decltype(b), DiffuseBsdf>)
                                     return b.pdf(d.to_local(wo), d.to_local(wi));
                                   else if constexpr (is<decltype(b), RefractionBsdf>)
                                     return drawn_only && !b.connects(wo, wi, backfacing) ? 0.0f
                                                                                          : b.pdf(wo, wi, backfacing);
                                   else return b.pdf(wo, wi);
                                 },
                                 components_[k]);
  return p;
}

BsdfSample MixtureBsdf::sample_mixture(const Vec3& wo, float u_lobe, const Vec2& u, bool backfacing,
                                       const DiffuseNormal& diffuse, const CoatNormal& coat) const {
  if (count_ == 0) return {};
  // Choose closure k, and reuse what is left of u_lobe for the closure's own lobe choice.
  int k = 0;
  float lower = 0.0f;
  while (k < count_ - 1 && u_lobe >= lower + probabilities_[k]) lower += probabilities_[k++];
  const float u_rest = std::max(std::min((u_lobe - lower) / probabilities_[k], 0.99999994f), 0.0f);
  const DiffuseFrame d(diffuse);
  const BsdfSample s = std::visit(
      [&](const auto& b) -> BsdfSample {
        if constexpr (is<decltype(b), std::monostate>) return {};
        else if constexpr (is<decltype(b), MaterialBsdf>)
          return b.sample(b.at(wo, backfacing, true, diffuse, coat), u_rest, u);
        else if constexpr (is<decltype(b), DiffuseBsdf>) {
          BsdfSample local = b.sample(d.to_local(wo), u_rest, u);
          local.wi = d.to_world(local.wi);
          return local;
        } else if constexpr (is<decltype(b), RefractionBsdf>) return b.sample(wo, u_rest, u, backfacing);
        else return b.sample(wo, u_rest, u);
      },
      components_[k]);
  if (!s.valid()) return {};
  if (s.is_delta) {
    BsdfSample d = s;
    d.weight = s.weight * (weights_[k] / probabilities_[k]);
    return d;
  }
  if (count_ == 1) {
    BsdfSample one = s;
    one.weight = s.weight * weights_[0];
    return one;
  }
  BsdfSample m;
  m.wi = s.wi;
  m.diffuse = s.diffuse;
  if (sample_is_own_eval(components_[k])) {
    // The others evaluated at wi, the sampled one as its sample says (Cycles' one-sample MIS).
    m.pdf = probabilities_[k] * s.pdf + pdf_mixture(wo, s.wi, backfacing, diffuse, coat, k);
    if (!(m.pdf > 0.0f)) return {};
    m.weight = (weights_[k] * s.weight * s.pdf + eval_mixture(wo, s.wi, backfacing, diffuse, coat, k).total()) / m.pdf;
    return m;
  }
  m.pdf = pdf_mixture(wo, s.wi, backfacing, diffuse, coat);
  if (!(m.pdf > 0.0f)) return {};
  m.weight = eval_mixture(wo, s.wi, backfacing, diffuse, coat).total() / m.pdf;
  return m;
}

bool MixtureBsdf::sample_is_own_eval(const Component& c) {
  if (const MaterialBsdf* m = std::get_if<MaterialBsdf>(&c)) return m->walks();
  return std::visit(
      [](const auto& b) { return SampleIsOwnEval<std::decay_t<decltype(b)>>::value; },
      c);
}

bool MixtureBsdf::transmits() const {
  for (int k = 0; k < count_; ++k) {
    if (const auto* m = std::get_if<MaterialBsdf>(&components_[k]); m && m->transmits()) return true;
    if (std::holds_alternative<TranslucentBsdf>(components_[k]) || std::holds_alternative<RefractionBsdf>(components_[k]) ||
        std::holds_alternative<PrincipledHairBsdf>(components_[k]) ||
        std::holds_alternative<HuangHairBsdf>(components_[k]) || std::holds_alternative<HairBsdf>(components_[k]))
      return true;
  }
  return false;
}

bool MixtureBsdf::hair_only() const {
  for (int k = 0; k < count_; ++k)
    if (!std::holds_alternative<HairBsdf>(components_[k])) return false;
  return count_ > 0;
}

bool MixtureBsdf::passes_straight() const {
  for (int k = 0; k < count_; ++k) {
    if (const auto* m = std::get_if<MaterialBsdf>(&components_[k]); m && m->passes_straight()) return true;
    if (const auto* h = std::get_if<HuangHairBsdf>(&components_[k]); h && h->may_pass()) return true;
  }
  return false;
}

Vec3 MixtureBsdf::straight_through(const View& v) const {
  Vec3 sum(0.0f);
  for (int k = 0; k < count_; ++k)
    if (const auto* m = std::get_if<MaterialBsdf>(&components_[k]); m && m->passes_straight())
      sum += weights_[k] * m->straight_through(m->at(v.wo, v.backfacing, v.diffuse, v.coat));
  return sum;
}

void MixtureBsdf::orient(const Frame& frame) {
  for (int k = 0; k < count_; ++k) {
    Component& c = components_[size_t(k)];
    if (GlossyBsdf* glossy = std::get_if<GlossyBsdf>(&c); glossy && glossy->anisotropic()) glossy->orient(frame);
    else if (MultiscatterGlossyBsdf* walk = std::get_if<MultiscatterGlossyBsdf>(&c); walk && walk->anisotropic())
      walk->orient(frame);
    else if (MetallicBsdf* metal = std::get_if<MetallicBsdf>(&c); metal && metal->anisotropic()) metal->orient(frame);
    else if (MaterialBsdf* material = std::get_if<MaterialBsdf>(&c)) material->orient(frame);
    else if (PrincipledHairBsdf* hair = std::get_if<PrincipledHairBsdf>(&c)) hair->orient(frame);
    else if (HairBsdf* strand = std::get_if<HairBsdf>(&c)) strand->orient(frame);
    else if (HuangHairBsdf* huang = std::get_if<HuangHairBsdf>(&c)) huang->orient(frame);
  }
}

void MixtureBsdf::finish_subsurface(SubsurfaceLobe& lobe, const Vec3& wo) const {
  if (lobe.layered_component < 0 || lobe.layered_component >= count_) return;
  const auto* m = std::get_if<MaterialBsdf>(&components_[size_t(lobe.layered_component)]);
  lobe.weight *= m ? m->subsurface_weight(wo) : Vec3(0.0f);
  lobe.layered_component = -1;
}

namespace {

// Principled v2 with Subsurface Weight as closure `component` of a vertex's mixture (weight w):
// the material its BSDF is built from (unwalked channels' radius 0: diffuse) and, when walked
// here (`subsurface` given and no walk yet), its lobe.
Material principled_v2_walk(const Material& m, const WalkState& walk, SubsurfaceLobe* subsurface, int component,
                            float w) {
  const bool first = subsurface && !subsurface->active();
  const Material walked = walked_only(m, first ? min_walk_radius(m, walk) : std::numeric_limits<float>::infinity());
  if (first) *subsurface = principled_v2_subsurface(walked, PrincipledV2Bsdf::dielectric_eta(walked), component, w);
  return walked;
}

}  // namespace

MixtureBsdf shade_material(const Scene& scene, uint32_t id, const ShaderGlobals& globals, bool textured,
                           BrdfModel model, const MaterialBsdf& prebuilt, Material& resolved,
                           glm::vec4* program_regs, ClosureList* closures, SubsurfaceLobe* subsurface,
                           const WalkState& walk, float wavelength) {
  const Mixture* mixture = scene.mixture(id);
  const bool diffuse_ancestor = !walk.walkable || walk.diffuse_ancestor;  // Principled v1 (3.x)
  if (!mixture) {
    resolved = scene.material(id);
    if (textured) scene.apply_textures(id, globals, resolved, program_regs);
    const bool dispersive = wavelength > 0.0f && dispersion::disperses(resolved, model);
    if (dispersive) resolved.wavelength = wavelength;
    if (subsurface && resolved.subsurface > 0.0f && model == BrdfModel::Principled) {
      if (diffuse_ancestor) return MixtureBsdf(MaterialBsdf(principled_as_diffuse(resolved), model));
      *subsurface = principled_subsurface(resolved);
    }
    if (subsurface && resolved.subsurface > 0.0f && !resolved.thin_wall && model == BrdfModel::PrincipledV2)
      return MixtureBsdf(MaterialBsdf(principled_v2_walk(resolved, walk, subsurface, 0, 1.0f), model));
    return textured || dispersive ? MixtureBsdf(MaterialBsdf(resolved, model)) : MixtureBsdf(prebuilt);
  }
  MixtureWeights w = scene.mixture_weights(id, globals, program_regs);
  weights_when_opaque(*mixture, w);  // the path did not pass through its Transparent closures
  resolved = Material{};
  resolved.base_color = Vec3(0.0f);
  resolved.metallic = 0.0f;
  MixtureBsdf bsdf;
  for (int k = 0; k < w.count; ++k) {
    if (!(w.weight[k] > 0.0f)) continue;
    const MixtureComponent& c = mixture->components[k];
    Material m = textured ? scene.textured_material(c.material, globals) : scene.material(c.material);
    if (wavelength > 0.0f && c.type == ClosureType::Principled && dispersion::disperses(m, model))
      m.wavelength = resolved.wavelength = wavelength;
    if (m.emission_under_layers && c.type == ClosureType::Principled) {
      if (max_component(m.emission) > 0.0f) bsdf.add_layered_emission(m, w.weight[k] * m.emission);
    } else {
      resolved.emission += w.weight[k] * m.emission;
    }
    if (closures) closures->add(c.type, w.weight[k], m);
    switch (c.type) {
      case ClosureType::Principled: {
        if (subsurface && m.subsurface > 0.0f && !m.thin_wall && model == BrdfModel::PrincipledV2) {
          const Material walked = principled_v2_walk(m, walk, subsurface, bsdf.size(), w.weight[k]);
          bsdf.add(MaterialBsdf(walked, model), w.weight[k], principled_sampling_albedo(walked));
          resolved.base_color += w.weight[k] * m.base_color * (1.0f - m.metallic);
          break;
        }
        const bool has_walk = subsurface && m.subsurface > 0.0f && model == BrdfModel::Principled;
        const bool walked = has_walk && !diffuse_ancestor && !subsurface->active();
        if (walked) *subsurface = principled_subsurface(m, w.weight[k]);
        if (has_walk && !walked) {
          // Not walked (after a diffuse bounce, as Cycles; or a second subsurface closure): Lambert.
          const Material diffuse = principled_as_diffuse(m);
          bsdf.add(MaterialBsdf(diffuse, model), w.weight[k], principled_sampling_albedo(diffuse));
        } else {
          bsdf.add(MaterialBsdf(m, model), w.weight[k], principled_sampling_albedo(m));
        }
        resolved.base_color += w.weight[k] * m.base_color * (1.0f - m.metallic);
        break;
      }
      case ClosureType::Subsurface: {
        const SubsurfaceLobe lobe = node_subsurface(walked_only(m, min_walk_radius(m, walk)), w.weight[k]);
        const bool walked = subsurface && !subsurface->active() && lobe.active();
        if (walked) *subsurface = lobe;
        // What is not walked is Lambert (Cycles: channels of too small a radius; all after a diffuse bounce).
        const Vec3 lambert = walked ? m.base_color * (Vec3(1.0f) - glm::sign(lobe.weight)) : m.base_color;
        if (max_component(lambert) > 0.0f) bsdf.add(DiffuseBsdf(lambert, 0.0f), w.weight[k], luminance(lambert));
        resolved.base_color += w.weight[k] * m.base_color;
        break;
      }
      case ClosureType::Diffuse:
      case ClosureType::DiffuseEnergyPreserving:
        bsdf.add(DiffuseBsdf(m.base_color, m.roughness, c.type == ClosureType::DiffuseEnergyPreserving), w.weight[k],
                 luminance(m.base_color));
        resolved.base_color += w.weight[k] * m.base_color;
        break;
      case ClosureType::Glossy:
        // Blender 4.x's Glossy (the PRINCIPLED_V2 model): Cycles 4.x's G and Multiscatter GGX.
        bsdf.add(GlossyBsdf(m.base_color, m.roughness, m.anisotropy, m.tangent, m.anisotropic_rotation,
                            model == BrdfModel::PrincipledV2, m.multiscatter_ggx, m.distribution),
                 w.weight[k], luminance(m.base_color));
        break;
      case ClosureType::GlossyMultiscatterV1:
        add_closure(bsdf, MultiscatterGlossyBsdf(m.base_color, m.roughness, m.anisotropy, m.tangent, m.anisotropic_rotation),
                    w.weight[k]);
        break;
      case ClosureType::MetallicF82:
      case ClosureType::MetallicConductor: {
        const bool conductor = c.type == ClosureType::MetallicConductor;
        add_closure(bsdf,
                    MetallicBsdf(conductor, conductor ? m.specular_tint_color : m.base_color,
                                 conductor ? m.sheen_tint_color : m.specular_tint_color, m.roughness, m.anisotropy,
                                 m.tangent, m.anisotropic_rotation, m.multiscatter_ggx, m.thin_film(), m.beckmann()),
                    w.weight[k]);
        break;
      }
      case ClosureType::Velvet: add_closure(bsdf, VelvetBsdf(m.base_color, m.roughness), w.weight[k]); break;
      case ClosureType::Sheen: add_closure(bsdf, SheenBsdf(m.base_color, m.roughness), w.weight[k]); break;
      case ClosureType::Translucent: add_closure(bsdf, TranslucentBsdf(m.base_color), w.weight[k]); break;
      case ClosureType::Refraction:
        add_closure(bsdf, RefractionBsdf(m.base_color, m.roughness, m.ior, m.beckmann(), m.glass_cycles4), w.weight[k]);
        break;
      case ClosureType::ToonDiffuse:
      case ClosureType::ToonGlossy:
      case ClosureType::ToonDiffuseCycles4:
      case ClosureType::ToonGlossyCycles4: {
        const bool glossy = c.type == ClosureType::ToonGlossy || c.type == ClosureType::ToonGlossyCycles4;
        const bool cycles4 = c.type == ClosureType::ToonDiffuseCycles4 || c.type == ClosureType::ToonGlossyCycles4;
        add_closure(bsdf, ToonBsdf(m.base_color, m.roughness, m.transmission_roughness, glossy, cycles4), w.weight[k]);
        break;
      }
      case ClosureType::PrincipledHair:
        // The strand's world direction (Cycles' dPdu), into the shading frame by orient().
        add_closure(bsdf, PrincipledHairBsdf(principled_hair_params(m, globals), globals.tangent), w.weight[k]);
        break;
      case ClosureType::PrincipledHairHuang:
        add_closure(bsdf, HuangHairBsdf(huang_hair_params(m, globals), globals.tangent, globals.on_curve,
                                          globals.curve_normal), w.weight[k]);
        break;
      case ClosureType::HairReflection:
      case ClosureType::HairTransmission:
        add_closure(bsdf, hair_bsdf(m, c.type == ClosureType::HairTransmission, globals), w.weight[k]);
        break;
      case ClosureType::Emission:
      case ClosureType::Transparent:
      case ClosureType::RayPortal:
      case ClosureType::Holdout: break;
    }
  }
  return bsdf;
}

}  // namespace torrance
