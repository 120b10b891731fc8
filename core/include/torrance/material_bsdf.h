// The BSDF of a material under the selected model: one value type the integrator can hold per
// material, forwarding eval / pdf / sample to the model's own class (see bsdf.h), plus the glass
// of transmissive materials (glass.h) as Cycles 3.4 combines them: a Principled BSDF with
// Transmission T and Metallic m is its opaque lobes (weights in principled.cpp) plus T (1 - m)
// glass; the Glass BSDF node is glass only. (PAPER scales its opaque lobes by 1 - T (1 - m).)
//
// Directions are in the shading frame turned towards the viewer (wo.z > 0), as for the opaque
// models; `backfacing` says the viewer is behind the GEOMETRIC surface (inside the glass), which
// only the glass needs: it is evaluated in its outward frame (z negated when backfacing).
// Transmitted directions have wi.z < 0; their light goes to the glossy part of LobeEval.
#pragma once

#include "torrance/cook_torrance.h"
#include "torrance/glass.h"
#include "torrance/principled.h"
#include "torrance/principled_v2.h"

#include <optional>
#include <variant>

namespace torrance {

class MaterialBsdf {
 public:
  MaterialBsdf(const Material& m, BrdfModel model) : bsdf_(make(m, model)) {
    if (!m.transmits()) return;
    const float metallic = clamp01(m.metallic), roughness = clamp01(m.roughness);
    if (m.glass_node) {
      glass_.emplace(roughness, roughness, m.ior, m.base_color, m.base_color, m.glass_beckmann);
      glass_weight_ = glass_probability_ = 1.0f;
      opaque_ = false;
      return;
    }
    const float refract_roughness = 1.0f - (1.0f - roughness) * (1.0f - clamp01(m.transmission_roughness));
    glass_.emplace(roughness, refract_roughness, m.ior, Vec3(1.0f), m.base_color);
    glass_weight_ = glass_probability_ = clamp01(m.transmission) * (1.0f - metallic);
    if (model == BrdfModel::Paper) opaque_scale_ = 1.0f - glass_weight_;
    opaque_ = glass_probability_ < 1.0f;
  }

  bool transmits() const { return glass_.has_value(); }

  // kGlass = false: the caller knows no material of the scene transmits (the integrator's
  // glass-free path), so the glass is not even checked for.
  template <bool kGlass = true>
  Vec3 eval(const Vec3& wo, const Vec3& wi, bool backfacing = false) const {
    return eval_lobes<kGlass>(wo, wi, backfacing).total();
  }
  template <bool kGlass = true>
  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi, bool backfacing = false) const {
    LobeEval f;
    if (!kGlass || opaque_) f = std::visit([&](const auto& b) { return b.eval_lobes(wo, wi); }, bsdf_);
    if (!kGlass || !glass_) return f;
    f.diffuse *= opaque_scale_;
    f.glossy = f.glossy * opaque_scale_ +
               glass_weight_ * glass_->eval(outward(wo, backfacing), outward(wi, backfacing));
    return f;
  }
  // The opaque lobes' choice of their specular lobe for this wo (lobe_mixture.h; 1 without
  // opaque lobes), which pdf and sample take as p_spec: a path vertex computes it once.
  float specular_probability(const Vec3& wo) const {
    return opaque_ ? std::visit([&](const auto& b) { return b.specular_probability(wo); }, bsdf_) : 1.0f;
  }
  template <bool kGlass = true>
  float pdf(const Vec3& wo, const Vec3& wi, bool backfacing = false) const {
    return pdf<kGlass>(wo, wi, backfacing, specular_probability(wo));
  }
  template <bool kGlass = true>
  float pdf(const Vec3& wo, const Vec3& wi, bool backfacing, float p_spec) const {
    if (!kGlass) return std::visit([&](const auto& b) { return b.pdf_given(wo, wi, p_spec); }, bsdf_);
    const float opaque = opaque_ ? std::visit([&](const auto& b) { return b.pdf_given(wo, wi, p_spec); }, bsdf_) *
                                       (1.0f - glass_probability_)
                                 : 0.0f;
    if (!glass_) return opaque;
    return opaque + glass_probability_ * glass_->pdf(outward(wo, backfacing), outward(wi, backfacing));
  }
  template <bool kGlass = true>
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u, bool backfacing = false) const {
    return sample<kGlass>(wo, u_lobe, u, backfacing, specular_probability(wo));
  }
  template <bool kGlass = true>
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u, bool backfacing, float p_spec) const {
    if (!kGlass || !glass_)
      return std::visit([&](const auto& b) { return b.sample_given(wo, u_lobe, u, p_spec); }, bsdf_);
    BsdfSample s;
    const float p = glass_probability_;
    if (u_lobe < p) {
      s = glass_->sample(outward(wo, backfacing), std::min(u_lobe / p, 0.99999994f), u);
      s.wi = outward(s.wi, backfacing);
      if (s.is_delta) s.weight *= glass_weight_ / p;
    } else {
      s = std::visit(
          [&](const auto& b) { return b.sample_given(wo, std::min((u_lobe - p) / (1.0f - p), 0.99999994f), u, p_spec); },
          bsdf_);
      if (s.is_delta) s.weight *= opaque_scale_ / (1.0f - p);
    }
    if (!s.valid() || s.is_delta) return s;
    // One-sample MIS over both parts: the density of either producing wi.
    s.pdf = pdf(wo, s.wi, backfacing, p_spec);
    if (!(s.pdf > 0.0f)) return BsdfSample{};
    s.weight = eval(wo, s.wi, backfacing) / s.pdf;
    return s;
  }

 private:
  using Variant = std::variant<CookTorranceBsdf, PrincipledBsdf, PrincipledV2Bsdf>;
  static Variant make(const Material& m, BrdfModel model) {
    if (model == BrdfModel::Principled) return PrincipledBsdf(m);
    if (model == BrdfModel::PrincipledV2) return PrincipledV2Bsdf(m);
    return CookTorranceBsdf(m);
  }
  static Vec3 outward(const Vec3& w, bool backfacing) { return backfacing ? Vec3(w.x, w.y, -w.z) : w; }

  Variant bsdf_;
  bool opaque_ = true;         // the model's lobes reflect something
  float opaque_scale_ = 1.0f;  // PAPER with transmission: 1 - glass weight
  std::optional<GlassBsdf> glass_;
  float glass_weight_ = 0.0f, glass_probability_ = 0.0f;
};

}  // namespace torrance
