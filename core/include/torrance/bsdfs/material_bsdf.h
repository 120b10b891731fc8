// The BSDF of a material under the selected model: one value type the integrator can hold per
// material, forwarding eval / pdf / sample to the model's own class (see bsdf.h), plus the glass
// of transmissive materials (glass.h) as Cycles 3.4 combines them: a Principled BSDF with
// Transmission T and Metallic m is its opaque lobes (weights in principled.cpp) plus T (1 - m)
// glass; the Glass BSDF node is glass only. (PAPER scales its opaque lobes by 1 - T (1 - m).)
// PRINCIPLED_V2's Transmission Weight T is Cycles 4.x's glass closure (principled_glass_v2.h),
// weight T (1 - m), its dielectric and diffuse layers keeping (1 - m)(1 - T) (principled_v2.h);
// the coat and the sheen above darken and tint it as the other layers (glass_layering).
//
// PRINCIPLED_V2 with Thin Wall (Blender 5.x): the transmission and the subsurface's translucency
// are thin_wall_v2.h's sheet (chosen with a fixed probability against the model's lobes), the
// same from both sides (no `backfacing`).
//
// Directions are in the shading frame turned towards the viewer (wo.z > 0), as for the opaque
// models; `backfacing` says the viewer is behind the GEOMETRIC surface (inside the glass), which
// only the glass needs: it is evaluated in its outward frame (z negated when backfacing).
// Transmitted directions have wi.z < 0; their light goes to the glossy part of LobeEval.
#pragma once

#include "torrance/bsdfs/cook_torrance.h"
#include "torrance/bsdfs/dispersion.h"
#include "torrance/bsdfs/glass.h"
#include "torrance/bsdfs/multiscatter_glass_bsdf.h"
#include "torrance/bsdfs/outward.h"
#include "torrance/bsdfs/principled.h"
#include "torrance/bsdfs/principled_glass_v2.h"
#include "torrance/bsdfs/principled_v2.h"
#include "torrance/bsdfs/thin_wall_v2.h"

#include <optional>
#include <type_traits>
#include <variant>

namespace torrance {

class MaterialBsdf {
 public:
  MaterialBsdf(const Material& m, BrdfModel model) : bsdf_(make(m, model)) {
    const float metallic = clamp01(m.metallic), roughness = clamp01(m.roughness);
    if (m.thin_wall && model == BrdfModel::PrincipledV2 && !m.glass_node) {
      make_thin_wall(m, metallic, roughness);
      return;
    }
    if (!m.glass_node && !(m.transmission > 0.0f && metallic < 1.0f)) return;
    if (m.glass_node) {
      if (m.glass_cycles4) {
        PrincipledGlassV2 glass = PrincipledGlassV2::glass_node(roughness, m.ior, m.base_color, m.multiscatter_ggx,
                                                                m.thin_film(), m.beckmann());
        if (m.transmission_anisotropic) glass.stretch_as_node(m.anisotropy, m.tangent, m.anisotropic_rotation);
        glass_.emplace(glass);
      } else if (m.multiscatter_walk && !m.beckmann())
        glass_.emplace(MultiscatterGlassBsdf(roughness, m.ior, m.base_color));
      else
        glass_.emplace(
            GlassBsdf(roughness, roughness, m.ior, m.base_color, m.base_color, m.beckmann(), false, m.thin_film()));
      glass_weight_ = glass_probability_ = 1.0f;
      opaque_ = false;
      return;
    }
    glass_weight_ = glass_probability_ = clamp01(m.transmission) * (1.0f - metallic);
    if (model == BrdfModel::PrincipledV2) {
      PrincipledGlassV2 glass(roughness, m.ior, m.specular_tint_color, m.base_color, m.multiscatter_ggx, m.thin_film(),
                              dispersion::refracting_ior(m));
      if (const auto* v2 = std::get_if<PrincipledV2Bsdf>(&bsdf_); v2 && m.transmission_anisotropic)
        glass.stretch(v2->shape());
      glass_.emplace(glass);
      // A coat or sheen over all-glass keeps its lobe (sampled at least 1 time in 10).
      if (m.coat_weight > 0.0f || m.sheen_weight > 0.0f) glass_probability_ = std::min(glass_probability_, 0.9f);
      opaque_ = glass_probability_ < 1.0f;
      return;
    }
    const float refract_roughness = 1.0f - (1.0f - roughness) * (1.0f - clamp01(m.transmission_roughness));
    // Blender 3.x's Multiscatter GGX above roughness 0.05 (Cycles 3.4): the walk, one roughness.
    if (m.multiscatter_walk && model == BrdfModel::Principled && roughness > 0.05f)
      glass_.emplace(MultiscatterGlassBsdf::principled(roughness, m.ior, m.base_color, m.specular_tint));
    else {
      GlassBsdf glass(roughness, refract_roughness, m.ior, Vec3(1.0f), m.base_color);
      const float tint = clamp01(m.specular_tint);
      if (model == BrdfModel::Principled && tint > 0.0f)
        glass.tint_reflection(glm::clamp(m.base_color, Vec3(0.0f), Vec3(1.0f)) * tint + Vec3(1.0f - tint));
      glass_.emplace(glass);
    }
    if (model == BrdfModel::Paper) opaque_scale_ = 1.0f - glass_weight_;
    opaque_ = glass_probability_ < 1.0f;
  }

  bool transmits() const { return glass_.has_value() || thin_.has_value(); }
  // Thin Wall's straight pass (the smooth sheet's delta transmission, thin_wall_v2.h): what rays
  // other than the camera's carry through it seen from v's wo, Cycles 5.x's Transparent closure
  // of that weight there (shadow rays pass it, thin_wall_shadow.h); 0 without one.
  bool passes_straight() const { return thin_ && thin_->transmission_is_delta() && glass_weight_ > 0.0f; }
  // An anisotropic model's (and Cycles 5.x's anisotropic glass's) tangent into the shading frame
  // (ggx_shape.h); before at().
  void orient(const Frame& frame) {
    std::visit(
        [&](auto& b) {
          if constexpr (!std::is_same_v<std::decay_t<decltype(b)>, CookTorranceBsdf>) b.orient(frame);
        },
        bsdf_);
    if (glass_)
      if (auto* v2 = std::get_if<PrincipledGlassV2>(&*glass_); v2 && v2->anisotropic()) v2->orient(frame);
  }
  // PRINCIPLED_V2's random-walk closure weight for the view wo (principled_v2.h; 0 otherwise).
  Vec3 subsurface_weight(const Vec3& wo) const {
    const auto* v2 = std::get_if<PrincipledV2Bsdf>(&bsdf_);
    return v2 && v2->has_subsurface() ? v2->subsurface_weight(wo.z) : Vec3(0.0f);
  }
  // The GGX alpha of the model's specular lobe (0 with glass: not asked for).
  float specular_alpha() const {
    return glass_ || thin_ ? 0.0f : std::visit([](const auto& b) { return b.alpha(); }, bsdf_);
  }
  // Whether the model's specular lobe or the glass is Blender 3.x's Multiscatter GGX walk
  // (principled.h, multiscatter_glass_bsdf.h): its samples count as their own eval in a mixture
  // (mixture_bsdf.h).
  bool walks() const {
    if (glass_walks()) return true;
    return !glass_ && !thin_ && std::visit([](const auto& b) { return lobe_mixture::walks(b); }, bsdf_);
  }
  bool glass_walks() const { return glass_ && std::holds_alternative<MultiscatterGlassBsdf>(*glass_); }
  // Whether the model's specular lobe is a delta (a mirror, with or without other lobes).
  bool has_delta() const {
    return !glass_ && !thin_ && std::visit([](const auto& b) { return b.has_delta(); }, bsdf_);
  }
  // Whether the material is a perfect mirror and nothing else: a delta reflection, no diffuse
  // lobe, no glass (mirror_images.h).
  bool pure_mirror() const {
    if (glass_ || thin_) return false;
    return std::visit(
        [](const auto& b) {
          return b.has_delta() && !lobe_mixture::coated(b) && !lobe_mixture::sheened(b) && b.specular_probability(Vec3(0.0f, 0.0f, 1.0f)) >= 1.0f &&
                 b.specular_probability(Vec3(0.99498744f, 0.0f, 0.1f)) >= 1.0f;
        },
        bsdf_);
  }

  // What eval, pdf and sample need of wo alone, prepared once per shading point: the model's
  // View (its at(wo), lobe_mixture.h) and `backfacing` (the glass's side).
  struct View {
    std::variant<CookTorranceBsdf::View, PrincipledBsdf::View, PrincipledV2Bsdf::View> lobes;
    Vec3 wo{0.0f, 0.0f, 1.0f};
    bool backfacing = false;
    ThinWallV2::View thin;  // Thin Wall's lobes seen from wo (with thin_)
    // The opaque lobes' choice of their specular lobe for this wo (1 without opaque lobes).
    float p_spec() const { return std::visit([](const auto& v) { return v.p_spec; }, lobes); }
  };
  // lobe_choice = false: without the lobe choice p_spec (1), for eval alone. diffuse, coat: the
  // diffuse lobe's and the coat's normals (bsdf.h).
  View at(const Vec3& wo, bool backfacing = false, bool lobe_choice = true, const DiffuseNormal& diffuse = {},
          const CoatNormal& coat = {}) const {
    const bool choice = lobe_choice && opaque_;
    View v{std::visit(
               [&](const auto& b) -> decltype(View::lobes) {
                 if constexpr (lobe_mixture::HasCoat<std::decay_t<decltype(b)>>::value)
                   return choice ? b.at(wo, coat) : b.geometry(wo, coat);
                 else return choice ? b.at(wo) : b.geometry(wo);
               },
               bsdf_),
           wo, backfacing, {}};
    if (diffuse.tilted) std::visit([&](auto& lv) { lv.diffuse_normal = diffuse; }, v.lobes);
    if (thin_) {
      const auto& lv = *std::get_if<PrincipledV2Bsdf::View>(&v.lobes);
      v.thin = thin_->at(wo, glass_weight_ * glass_layering(v), lv.terms.translucent);
    }
    return v;
  }
  View at(const Vec3& wo, bool backfacing, const DiffuseNormal& diffuse, const CoatNormal& coat = {}) const {
    return at(wo, backfacing, true, diffuse, coat);
  }
  // passes_straight()'s weight seen from v's wo.
  Vec3 straight_through(const View& v) const { return passes_straight() ? v.thin.transmit : Vec3(0.0f); }

  // kGlass = false: the caller knows no material of the scene transmits (the integrator's
  // glass-free path), so the glass is not even checked for.
  template <bool kGlass = true>
  LobeEval eval_lobes(const View& v, const Vec3& wi) const {
    LobeEval f;
    if (!kGlass || opaque_) f = visit(v, [&](const auto& b, const auto& lv) { return b.eval_lobes(lv, wi); });
    if (kGlass && thin_) {
      const LobeEval t = thin_->eval(v.thin, wi);
      f.diffuse += t.diffuse;
      f.glossy += t.glossy;
      return f;
    }
    if (!kGlass || !glass_) return f;
    f.diffuse *= opaque_scale_;
    f.glossy = f.glossy * opaque_scale_ +
               glass_weight_ * glass_layering(v) * glass([&](const auto& g) {
                 return g.eval(outward(v.wo, v.backfacing), outward(wi, v.backfacing));
               });
    return f;
  }
  template <bool kGlass = true>
  float pdf(const View& v, const Vec3& wi) const {
    if (!kGlass) return visit(v, [&](const auto& b, const auto& lv) { return b.pdf(lv, wi); });
    const float opaque =
        opaque_ ? visit(v, [&](const auto& b, const auto& lv) { return b.pdf(lv, wi); }) * (1.0f - glass_probability_)
                : 0.0f;
    if (thin_) return opaque + glass_probability_ * thin_->pdf(v.thin, wi);
    if (!glass_) return opaque;
    return opaque + glass_probability_ * glass([&](const auto& g) {
             return g.pdf(outward(v.wo, v.backfacing), outward(wi, v.backfacing));
           });
  }
  template <bool kGlass = true>
  BsdfSample sample(const View& v, float u_lobe, const Vec2& u) const {
    if (!kGlass || !transmits()) return visit(v, [&](const auto& b, const auto& lv) { return b.sample(lv, u_lobe, u); });
    BsdfSample s;
    const float p = glass_probability_;
    if (u_lobe < p && thin_) {
      s = thin_->sample(v.thin, std::min(u_lobe / p, 0.99999994f), u);
      if (s.is_delta) s.weight /= p;
    } else if (u_lobe < p) {
      s = glass([&](const auto& g) {
        return g.sample(outward(v.wo, v.backfacing), std::min(u_lobe / p, 0.99999994f), u);
      });
      s.wi = outward(s.wi, v.backfacing);
      if (s.is_delta) s.weight *= glass_weight_ * glass_layering(v) / p;
      else if (s.valid() && glass_walks()) return own_walk_sample(v, s);
    } else {
      s = visit(v, [&](const auto& b, const auto& lv) {
        return b.sample(lv, std::min((u_lobe - p) / (1.0f - p), 0.99999994f), u);
      });
      if (s.is_delta) s.weight *= opaque_scale_ / (1.0f - p);
    }
    if (!s.valid() || s.is_delta) return s;
    // One-sample MIS over both parts: the density of either producing wi.
    s.pdf = pdf(v, s.wi);
    if (!(s.pdf > 0.0f)) return BsdfSample{};
    s.weight = eval_lobes(v, s.wi).total() / s.pdf;
    return s;
  }

  // The same, preparing wo for this one query (p_spec: the lobe choice, if known).
  template <bool kGlass = true>
  Vec3 eval(const Vec3& wo, const Vec3& wi, bool backfacing = false) const {
    return eval_lobes<kGlass>(wo, wi, backfacing).total();
  }
  template <bool kGlass = true>
  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi, bool backfacing = false) const {
    return eval_lobes<kGlass>(at(wo, backfacing, false), wi);
  }
  float specular_probability(const Vec3& wo) const { return at(wo).p_spec(); }
  template <bool kGlass = true>
  float pdf(const Vec3& wo, const Vec3& wi, bool backfacing = false) const {
    return pdf<kGlass>(at(wo, backfacing), wi);
  }
  template <bool kGlass = true>
  float pdf(const Vec3& wo, const Vec3& wi, bool backfacing, float p_spec) const {
    return pdf<kGlass>(with_choice(at(wo, backfacing, false), p_spec), wi);
  }
  template <bool kGlass = true>
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u, bool backfacing = false) const {
    return sample<kGlass>(at(wo, backfacing), u_lobe, u);
  }
  template <bool kGlass = true>
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u, bool backfacing, float p_spec) const {
    return sample<kGlass>(with_choice(at(wo, backfacing, false), p_spec), u_lobe, u);
  }

 private:
  // Calls f(model, its view) for the model of this material and v (prepared by at()).
  template <typename F>
  decltype(auto) visit(const View& v, F&& f) const {
    if (const auto* p = std::get_if<PrincipledBsdf::View>(&v.lobes)) return f(*std::get_if<PrincipledBsdf>(&bsdf_), *p);
    if (const auto* c = std::get_if<CookTorranceBsdf::View>(&v.lobes))
      return f(*std::get_if<CookTorranceBsdf>(&bsdf_), *c);
    return f(*std::get_if<PrincipledV2Bsdf>(&bsdf_), *std::get_if<PrincipledV2Bsdf::View>(&v.lobes));
  }
  // The walking glass's sample s (its weight the walk's, not eval / pdf): its own eval
  // (weight x pdf) in place of the glass's eval, plus the opaque lobes', over the mixture's pdf
  // (lobe_mixture.h's walk, Cycles' one-sample MIS).
  BsdfSample own_walk_sample(const View& v, BsdfSample s) const {
    const Vec3 own = glass_weight_ * glass_layering(v) * s.weight * s.pdf;
    s.pdf = pdf(v, s.wi);
    if (!(s.pdf > 0.0f)) return BsdfSample{};
    const Vec3 opaque =
        opaque_ ? visit(v, [&](const auto& b, const auto& lv) { return b.eval_lobes(lv, s.wi); }).total() * opaque_scale_
                : Vec3(0.0f);
    s.weight = (opaque + own) / s.pdf;
    return s;
  }
  static View with_choice(View v, float p_spec) {
    std::visit([&](auto& lv) { lv.p_spec = p_spec; }, v.lobes);
    return v;
  }

  using Variant = std::variant<CookTorranceBsdf, PrincipledBsdf, PrincipledV2Bsdf>;
  static Variant make(const Material& m, BrdfModel model) {
    if (model == BrdfModel::Principled) return PrincipledBsdf(m);
    if (model == BrdfModel::PrincipledV2) return PrincipledV2Bsdf(m);
    return CookTorranceBsdf(m);
  }
  // What the glass keeps under PRINCIPLED_V2's coat and sheen seen from v's wo (Cycles layers
  // them over its transmission closure as over the other layers); 1 for the other models.
  static Vec3 glass_layering(const View& v) {
    const auto* lv = std::get_if<PrincipledV2Bsdf::View>(&v.lobes);
    return lv ? lv->terms.coat.base_weight * SheenV2::keep(lv->terms.sheen) : Vec3(1.0f);
  }
  // Thin Wall: the sheet, weighted transmission (1 - metallic), chosen with a probability that
  // follows its share of the weights (at most 0.9 while the model's lobes reflect something).
  void make_thin_wall(const Material& m, float metallic, float roughness) {
    thin_.emplace(
        ThinWallV2(roughness, m.ior, m.specular_tint_color, m.base_color, m.thin_film(), m.diffuse_roughness));
    glass_weight_ = clamp01(m.transmission) * (1.0f - metallic);
    const float g = std::isfinite(m.subsurface_anisotropy) ? m.subsurface_anisotropy : 0.0f;
    const float translucent = (1.0f - metallic) * (1.0f - clamp01(m.transmission)) * clamp01(m.subsurface) *
                              clamp01(0.5f * (1.0f + g)) * clamp01(luminance(glm::min(m.base_color, Vec3(1.0f))));
    glass_probability_ = clamp01(glass_weight_ + translucent);
    const bool lobes_above = glass_weight_ < 1.0f || m.coat_weight > 0.0f || m.sheen_weight > 0.0f;
    if (lobes_above) glass_probability_ = std::min(glass_probability_, 0.9f);
    opaque_ = glass_probability_ < 1.0f;
  }
  // Calls f(the glass) (PRINCIPLED_V2's or Cycles 3.4's); only with glass_.
  template <typename F>
  decltype(auto) glass(F&& f) const {
    if (const auto* v2 = std::get_if<PrincipledGlassV2>(&*glass_)) return f(*v2);
    if (const auto* walk = std::get_if<MultiscatterGlassBsdf>(&*glass_)) return f(*walk);
    return f(*std::get_if<GlassBsdf>(&*glass_));
  }

  Variant bsdf_;
  bool opaque_ = true;         // the model's lobes reflect something
  float opaque_scale_ = 1.0f;  // PAPER with transmission: 1 - glass weight
  std::optional<std::variant<GlassBsdf, PrincipledGlassV2, MultiscatterGlassBsdf>> glass_;
  std::optional<ThinWallV2> thin_;  // PRINCIPLED_V2's Thin Wall (instead of glass_)
  float glass_weight_ = 0.0f, glass_probability_ = 0.0f;
};

}  // namespace torrance
