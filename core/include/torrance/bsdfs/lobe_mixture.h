// Sampling shared by the metallic/roughness BSDFs (PAPER, PRINCIPLED, PRINCIPLED_V2): a diffuse
// lobe sampled by the cosine and a GGX lobe sampled by visible normals, chosen with the BSDF's
// specular_probability(wo) (one-sample MIS: the pdf is the mixture of both); below
// ggx::kDeltaAlpha the GGX lobe is a mirror whose reflectance the BSDF gives as
// mirror_reflectance(wo). Only the models' eval() and lobe weights differ.
//
// A model with a coat (PRINCIPLED, PRINCIPLED_V2: principled_coat.h) adds a third lobe, chosen
// first with its View's p_coat (0 without a coat: then nothing of it runs), by naming
// coat_pdf(view, wi), coat_sample(view, u), coat_is_delta() and coat_mirror_reflectance(view); the
// coat works in the frame of its View's coat_normal (bsdf.h; coat_pdf / coat_sample below).
// A model with a sheen layer above that (PRINCIPLED_V2: principled_sheen.h) adds a fourth lobe,
// chosen before all others with its View's p_sheen (0 without a sheen), by naming
// sheen_pdf(view, wi) and sheen_sample(view, u) of its own View; the sheen is a diffuse lobe.
//
// A model whose specular lobe may be a random walk (PRINCIPLED with Blender 3.x's Multiscatter
// GGX: microsurface_walk.h) names walks(), walk_pdf(wo, wi), walk_sample(wo, u_lobe, u) and
// eval_lobes_but_walk(view, wi). When it walks, the lobe's density is the walk's estimate and a
// direction the walk drew is weighted as Cycles weighs it: the walk's weight x its pdf in place of
// the lobe's eval, plus the other lobes' eval, over the mixture's pdf (so that the sum stays
// unbiased for the walk whose true density is unknown; mixture_bsdf.h's kSampleIsOwnEval).
//
// A shading point asks its BSDF several times with one wo (light choice, the light sample's eval
// and MIS pdf, the BSDF sample's pdf and eval), so each model prepares what depends on wo alone
// once, in a View (the model's at(wo)), which its eval/pdf/sample take instead of wo.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/ggx_shape.h"
#include "torrance/util/sampling.h"

#include <algorithm>
#include <type_traits>

namespace torrance::lobe_mixture {

// The probability of choosing the specular lobe, from the estimated reflectances (luminances) of
// the specular and diffuse lobes for this wo: spec / (spec + diff), clamped to [0.1, 0.9] so that
// neither lobe's density becomes tiny while it reflects; 1 or 0 when only one lobe reflects.
// Each BSDF's specular_probability(wo) estimates spec and diff its own way and calls this.
inline float specular_probability(float spec, float diff) {
  if (!(diff > 0.0f)) return 1.0f;
  if (!(spec > 0.0f)) return 0.0f;
  return std::min(std::max(spec / (spec + diff), 0.1f), 0.9f);
}

// The mixture's terms of wo, the base of every model's View: the GGX density factors of wo
// (ggx::reflected_pdf = g1_o D(h) / four_cos_o) and the lobe choice p_spec.
struct View {
  Vec3 wo{0.0f, 0.0f, 1.0f};
  float g1_o = 0.0f;       // the GGX shape's G1(wo)
  float four_cos_o = 0.0f;  // 4 wo.z
  float p_spec = 1.0f;     // bsdf.specular_probability(wo), of the lobes other than the coat
  float p_coat = 0.0f;     // the coat lobe's probability (models with a coat)
  float p_sheen = 0.0f;    // the sheen lobe's probability (models with a sheen layer)
  DiffuseNormal diffuse_normal;  // the diffuse lobe's (bsdf.h); PRINCIPLED_V2 alone reads it
  CoatNormal coat_normal;        // the coat's (bsdf.h; models with a coat), set before at()'s terms
};

// A model's coat lobe (principled_coat.h, in its own frame) seen through v's coat normal: its
// pdf of wi, a sampled direction, and its mirror direction (all in the shading frame).
template <typename Coat>
float coat_pdf(const Coat& coat, const View& v, const Vec3& wi) {
  return coat.pdf(v.coat_normal.to_coat(v.wo), v.coat_normal.to_coat(wi));
}
template <typename Coat>
Vec3 coat_sample(const Coat& coat, const View& v, const Vec2& u) {
  return v.coat_normal.from_coat(coat.sample(v.coat_normal.to_coat(v.wo), u));
}
inline Vec3 coat_mirror(const View& v) {
  const Vec3 wo = v.coat_normal.to_coat(v.wo);
  return v.coat_normal.from_coat(Vec3(-wo.x, -wo.y, wo.z));
}

// Whether a model may walk (names walks; see above), and whether it does.
template <typename Bsdf, typename = void>
struct HasWalk : std::false_type {};
template <typename Bsdf>
struct HasWalk<Bsdf, std::void_t<decltype(&Bsdf::walks)>> : std::true_type {};
template <typename Bsdf>
bool walks(const Bsdf& bsdf) {
  if constexpr (HasWalk<Bsdf>::value) return bsdf.walks();
  return false;
}

// Whether a model has a coat lobe (names coat_pdf).
template <typename Bsdf, typename = void>
struct HasCoat : std::false_type {};
template <typename Bsdf>
struct HasCoat<Bsdf, std::void_t<decltype(&Bsdf::coat_pdf)>> : std::true_type {};

// Whether a model's material has a coat (false for models without one).
template <typename Bsdf>
bool coated(const Bsdf& bsdf) {
  if constexpr (HasCoat<Bsdf>::value) return bsdf.has_coat();
  return false;
}

// Whether a model has a sheen lobe of its own (names sheen_pdf).
template <typename Bsdf, typename = void>
struct HasSheen : std::false_type {};
template <typename Bsdf>
struct HasSheen<Bsdf, std::void_t<decltype(&Bsdf::sheen_pdf)>> : std::true_type {};

// Whether a model's material has a sheen lobe (false for models without one).
template <typename Bsdf>
bool sheened(const Bsdf& bsdf) {
  if constexpr (HasSheen<Bsdf>::value) return bsdf.has_sheen();
  return false;
}

// The lobe choice's probability of the coat, from estimated reflectances (coat and the rest): the
// coat's share, clamped to [0.1, 0.9] as specular_probability.
inline float coat_probability(float coat, float rest) {
  if (!(coat > 0.0f)) return 0.0f;
  return 1.0f - specular_probability(rest, coat);
}

// The coat's sampled direction (models with a coat; never called for the others).
template <typename Bsdf, typename View>
Vec3 coat_direction(const Bsdf& bsdf, const View& v, const Vec2& u) {
  if constexpr (HasCoat<Bsdf>::value) return bsdf.coat_sample(v, u);
  return Vec3(0.0f);
}

// The sheen's sampled direction (models with a sheen; never called for the others).
template <typename Bsdf, typename View>
Vec3 sheen_direction(const Bsdf& bsdf, const View& v, const Vec2& u) {
  if constexpr (HasSheen<Bsdf>::value) return bsdf.sheen_sample(v, u);
  return Vec3(0.0f);
}

// A cosine-distributed direction about the diffuse lobe's normal d.
inline Vec3 sample_diffuse(const DiffuseNormal& d, const Vec2& u) {
  const Vec3 local = sample_cosine_hemisphere(u);
  return d.tilted ? Frame(d.n).to_world(local) : local;
}

// Fills the geometric terms of `v` for wo (not p_spec: the model's at() adds it).
inline void prepare(View& v, const Vec3& wo, const ggx::Shape& shape) {
  v.wo = wo;
  v.g1_o = shape.G1(wo);
  v.four_cos_o = 4.0f * wo.z;
}

// The mixture's pdf of wi seen from the prepared v, its specular lobe the walk's estimate (kWalk)
// or GGX's visible normals'.
template <bool kWalk, typename Bsdf, typename V>
float pdf_of(const Bsdf& bsdf, const V& v, const Vec3& wi, const ggx::Shape& shape) {
  const Vec3& wo = v.wo;
  if (wo.z <= 0.0f) return 0.0f;
  float pdf = (1.0f - v.p_spec) * cosine_hemisphere_pdf(v.diffuse_normal.cosine(wi));
  if (wi.z > 0.0f && !bsdf.has_delta() && v.p_spec > 0.0f) {
    if constexpr (kWalk) pdf += v.p_spec * bsdf.walk_pdf(wo, wi);
    else pdf += v.p_spec * (v.g1_o * shape.D(glm::normalize(wo + wi)) / v.four_cos_o);
  }
  if constexpr (HasCoat<Bsdf>::value) {
    if (v.p_coat > 0.0f) pdf = (1.0f - v.p_coat) * pdf + v.p_coat * bsdf.coat_pdf(v, wi);
  }
  if constexpr (HasSheen<Bsdf>::value) {
    if (v.p_sheen > 0.0f) pdf = (1.0f - v.p_sheen) * pdf + v.p_sheen * bsdf.sheen_pdf(v, wi);
  }
  return pdf;
}

// pdf_of<true>, out of line (see pdf below).
template <typename Bsdf, typename V>
[[gnu::noinline]] float walking_pdf(const Bsdf& bsdf, const V& v, const Vec3& wi, const ggx::Shape& shape) {
  return pdf_of<true>(bsdf, v, wi, shape);
}

// The mixture's pdf of wi seen from the prepared v (Bsdf::View, or View for models without a
// sheen). The walk's is a call of its own: GGX's stays free of it (and of the registers it saves).
template <typename Bsdf, typename V>
float pdf(const Bsdf& bsdf, const V& v, const Vec3& wi, const ggx::Shape& shape) {
  if constexpr (HasWalk<Bsdf>::value) {
    if (bsdf.walks()) return walking_pdf(bsdf, v, wi, shape);
  }
  return pdf_of<false>(bsdf, v, wi, shape);
}

// The specular lobe's walk drawn (u_lobe: the lobe choice's number, rescaled), weighed as above.
// Out of line: only Blender 3.x's Multiscatter GGX walks, and inlined it would push GGX's own
// sampling out of sample() below.
template <typename Bsdf>
[[gnu::noinline]] BsdfSample sample_walk(const Bsdf& bsdf, const typename Bsdf::View& v, float u_lobe, const Vec2& u,
                                         const ggx::Shape& shape) {
  const BsdfSample walk = bsdf.walk_sample(v.wo, u_lobe, u);
  if (!walk.valid()) return BsdfSample{};
  BsdfSample s;
  s.wi = walk.wi;
  s.pdf = pdf(bsdf, v, s.wi, shape);
  if (!(s.pdf > 0.0f)) return BsdfSample{};
  s.weight = (bsdf.eval_lobes_but_walk(v, s.wi).total() + walk.weight * walk.pdf) / s.pdf;
  return s;
}

// Samples the mixture seen from the prepared v (Bsdf::View derives from View); eval and pdf of
// the sampled direction use the same view.
template <typename Bsdf>
BsdfSample sample(const Bsdf& bsdf, const typename Bsdf::View& v, float u_lobe, const Vec2& u,
                  const ggx::Shape& shape) {
  const Vec3& wo = v.wo;
  BsdfSample s;
  if (wo.z <= 0.0f) return s;
  float others = 1.0f;  // the probability of the lobes other than the sheen and the coat
  bool sheen = false, coat = false;
  if constexpr (HasSheen<Bsdf>::value) {
    if (v.p_sheen > 0.0f) {
      sheen = u_lobe < v.p_sheen;
      others = 1.0f - v.p_sheen;
      if (!sheen) u_lobe = std::min((u_lobe - v.p_sheen) / others, 0.99999994f);
    }
  }
  if constexpr (HasCoat<Bsdf>::value) {
    if (v.p_coat > 0.0f && !sheen) {
      coat = u_lobe < v.p_coat;
      if (coat && bsdf.coat_is_delta()) {
        s.wi = coat_mirror(v);
        s.weight = bsdf.coat_mirror_reflectance(v) / (v.p_coat * others);
        s.is_delta = true;
        return s;
      }
      others *= 1.0f - v.p_coat;
      u_lobe = std::min((u_lobe - v.p_coat) / (1.0f - v.p_coat), 0.99999994f);
    }
  }
  if (sheen) {
    s.wi = sheen_direction(bsdf, v, u);
    s.diffuse = true;
    if (!(s.wi.z > 0.0f)) return BsdfSample{};
  } else if (coat) {
    s.wi = coat_direction(bsdf, v, u);
    if (v.coat_normal.cosine(s.wi) <= 0.0f) return BsdfSample{};
  } else if (u_lobe < v.p_spec) {
    if (bsdf.has_delta()) {
      s.wi = Vec3(-wo.x, -wo.y, wo.z);
      s.weight = bsdf.mirror_reflectance(wo) / (v.p_spec * others);
      s.is_delta = true;
      return s;
    }
    if constexpr (HasWalk<Bsdf>::value) {
      if (bsdf.walks()) return sample_walk(bsdf, v, u_lobe / v.p_spec, u, shape);
    }
    s.wi = ggx::reflect(wo, shape.sample_visible_normal(wo, u));
    if (s.wi.z <= 0.0f) return BsdfSample{};
  } else {
    s.wi = sample_diffuse(v.diffuse_normal, u);
    s.diffuse = true;
    if (v.diffuse_normal.cosine(s.wi) <= 0.0f) return BsdfSample{};
  }
  s.pdf = pdf(bsdf, v, s.wi, shape);
  if (!(s.pdf > 0.0f)) return BsdfSample{};
  s.weight = bsdf.eval_lobes(v, s.wi).total() / s.pdf;
  return s;
}

// The queries every model answers the same way from its geometry(wo), at(wo), eval_lobes(view, wi)
// and shape() (its GGX lobe, ggx_shape.h): pdf and sample of a prepared view, and eval, pdf and sample preparing wo for one
// query. A model derives from Queries<Model> and names `using Queries<Model>::eval_lobes;` beside
// its own eval_lobes(view, wi). (View overloads are templates: the model is incomplete here.)
template <typename Bsdf>
class Queries {
 public:
  template <typename View>
  float pdf(const View& v, const Vec3& wi) const {
    return lobe_mixture::pdf(self(), v, wi, self().shape());
  }
  template <typename View>
  BsdfSample sample(const View& v, float u_lobe, const Vec2& u) const {
    return lobe_mixture::sample(self(), v, u_lobe, u, self().shape());
  }
  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const { return self().eval_lobes(self().geometry(wo), wi); }
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const { return pdf(self().at(wo), wi); }
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const { return sample(self().at(wo), u_lobe, u); }

 private:
  const Bsdf& self() const { return static_cast<const Bsdf&>(*this); }
};

}  // namespace torrance::lobe_mixture
