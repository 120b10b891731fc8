// Principled BSDF, "PRINCIPLED" model: Blender 3.4's Principled BSDF (v1) as Cycles 3.4 renders it
// with the GGX distribution, so that Torrance and Cycles differ by noise only. Transmission only scales these lobes down (see the constructor); its
// glass is GlassBsdf, which MaterialBsdf adds.
//
//   diffuse  Burley's lobe weighted by (1 - metallic), using the unsquared roughness for
//            retro-reflection; it is NOT scaled by (1 - F): the lobes add (and can exceed 1).
//   specular GGX, alpha = roughness^2, separable exact Smith G = G1(wo) G1(wi) with
//            G1 = 2 / (1 + sqrt(1 + alpha^2 tan^2)); Anisotropic a stretches it along the
//            tangent (ggx_shape.h): alpha_x = alpha / s, alpha_y = alpha s, s = sqrt(1 - 0.9 a),
//            each at most 1, the tangent turned by Anisotropic Rotation (turns) about the normal,
//            F = cspec0 (1 - F_H) + F_H, F_H = (F_dielectric(wi.h, eta) - F0) / (1 - F0),
//            F0 = 0.08 specular, eta from F0, and
//            cspec0 = 0.08 specular mix(1, tint colour, specular_tint) (1 - metallic) + base metallic.
//   mirror   below ggx::kDeltaAlpha the specular lobe is a delta with reflectance F(n.wo).
//   multiscatter  Blender 3.x's Multiscatter GGX (Material::multiscatter_walk), as Cycles 3.4:
//            above roughness 0.075 the specular lobe is the random walk of microsurface_walk.h,
//            F inside the walk at every facet; its pdf is the walk's estimate and a sample drawn
//            from it counts as its own eval (lobe_mixture.h), as Cycles' closures do.
//   clearcoat  Cycles 3.4's clearcoat lobe, added on top (principled_coat.h: ClearcoatV1), in the
//            glossy part of LobeEval, about the View's coat_normal (Clearcoat Normal, bsdf.h).
//   subsurface  with Subsurface > 0 the diffuse lobe's colour is the base colour mixed towards
//            Subsurface Color and its Lambertian part is left to the random walk (subsurface/), as
//            Cycles 3.4's BSSRDF setup leaves its retro-reflection as a BSDF.
//   sheen    Cycles 3.4's principled sheen (principled_sheen.h: SheenV1), added to the diffuse
//            lobe and sampled with it by the cosine.
// Sampling picks a lobe by estimated reflectance, then visible GGX normals or the cosine. With a
// clearcoat all three lobes are chosen with Cycles' closure odds (w F(wo.z), the mean diffuse
// colour, the mean specular Fresnel): the clearcoat's stated density is not the one it draws
// from, as in Cycles, and the bias this gives every lobe depends on the odds.
// See bsdf.h for the conventions (eval includes the cosine).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/lobe_mixture.h"
#include "torrance/bsdfs/microfacet.h"
#include "torrance/bsdfs/microsurface_walk.h"
#include "torrance/bsdfs/principled_coat.h"
#include "torrance/bsdfs/principled_sheen.h"

namespace torrance {

// Unpolarised Fresnel reflectance of a dielectric interface with relative IOR eta (> 0).
float fresnel_dielectric(float cos_i, float eta);

// The colour of Cycles 3.x's *_FRESNEL microfacet closures (interpolate_fresnel_color): cspec0
// blended to white by the dielectric Fresnel at cos_ih, normalised past f0 = F_dielectric(1, eta):
// cspec0 (1 - F_H) + F_H, F_H = (F_dielectric(cos_ih, eta) - f0) / (1 - f0), clamped to [0, 1] (at
// normal incidence rounding makes it a tiny negative number); white when f0 >= 1.
Vec3 fresnel_interpolated(const Vec3& cspec0, float cos_ih, float eta, float f0);

class PrincipledBsdf : public lobe_mixture::Queries<PrincipledBsdf> {
 public:
  explicit PrincipledBsdf(const Material& m);

  // What eval, pdf and sample need of wo alone (lobe_mixture.h), prepared once per shading point.
  struct View : lobe_mixture::View {
    using Model = PrincipledBsdf;
    float burley_o = 0.0f;  // the Burley diffuse's Schlick weight (1 - wo.z)^5
  };
  // coat: the clearcoat's normal (bsdf.h; by default the shading normal).
  View at(const Vec3& wo, const CoatNormal& coat = {}) const;        // with the lobe choice p_spec
  View geometry(const Vec3& wo, const CoatNormal& coat = {}) const;  // without it (p_spec = 1): enough for eval

  LobeEval eval_lobes(const View& v, const Vec3& wi) const { return eval_parts<true>(v, wi); }
  using lobe_mixture::Queries<PrincipledBsdf>::eval_lobes;  // pdf, sample, eval: lobe_mixture::Queries

  float alpha() const { return alpha_; }
  const ggx::Shape& shape() const { return shape_; }
  // Anisotropic: the tangent into the shading frame (ggx_shape.h); before at().
  void orient(const Frame& frame) { shape_.orient(frame); }
  bool has_delta() const { return specular_ == Specular::Mirror; }
  Vec3 mirror_reflectance(const Vec3& wo) const { return fresnel(wo.z); }
  float specular_probability(const Vec3& wo) const;
  Vec3 fresnel(float cos_ih) const;

  // Multiscatter GGX's walk (lobe_mixture.h): whether the specular lobe is one, its pdf estimate,
  // a sample (weight: the walk's throughput times the lobe's weight) and the other lobes' eval.
  bool walks() const { return specular_ == Specular::Walk; }
  float walk_pdf(const Vec3& wo, const Vec3& wi) const { return walk().pdf(wo, wi); }
  BsdfSample walk_sample(const Vec3& wo, float u_lobe, const Vec2& u) const {
    BsdfSample s = walk().sample(wo, u_lobe, u);
    s.weight *= specular_weight_;
    return s;
  }
  LobeEval eval_lobes_but_walk(const View& v, const Vec3& wi) const { return eval_parts<false>(v, wi); }

  // The clearcoat lobe (lobe_mixture.h).
  bool has_coat() const { return coat_.active(); }
  float coat_pdf(const lobe_mixture::View& v, const Vec3& wi) const { return lobe_mixture::coat_pdf(coat_, v, wi); }
  Vec3 coat_sample(const lobe_mixture::View& v, const Vec2& u) const { return lobe_mixture::coat_sample(coat_, v, u); }
  bool coat_is_delta() const { return coat_.is_delta(); }
  Vec3 coat_mirror_reflectance(const lobe_mixture::View& v) const {
    return Vec3(coat_.mirror_reflectance(v.coat_normal.cosine(v.wo)));
  }
  const ClearcoatV1& coat() const { return coat_; }
  const SheenV1& sheen() const { return sheen_; }

 private:
  // The lobes' eval, the walk's (Specular::Walk) with kWithWalk.
  template <bool kWithWalk>
  LobeEval eval_parts(const View& v, const Vec3& wi) const;
  // Specular::Walk: the walk, made where it is asked for from shape_ (oriented) and the lobe's
  // Fresnel (held, it would make every PrincipledBsdf 80 bytes larger to build).
  microsurface::Walk walk() const;

  Vec3 diffuse_color_;  // (1 - metallic) (1 - transmission) * base colour
  float diffuse_luminance_;  // luminance(diffuse_color_), for the lobe choice
  float specular_weight_;  // 1 - transmission (1 - metallic): the glass takes the rest
  Vec3 cspec0_;
  float roughness_, alpha_, eta_, f0_;
  ggx::Shape shape_;  // the specular lobe: alpha_, or stretched by Anisotropic
  // What the specular lobe is, fixed at construction (eval, pdf and sample ask it every time):
  // GGX, a mirror (below ggx::kDeltaAlpha) or Multiscatter GGX's walk (walk()).
  enum class Specular : uint8_t { Ggx, Mirror, Walk };
  Specular specular_ = Specular::Ggx;
  ClearcoatV1 coat_;
  SheenV1 sheen_;
  // Subsurface (subsurface_lobe.h): the diffuse keeps its retro-reflection, its Lambertian part only
  // in lambert_channels_ (where the walk does not go).
  bool subsurface_ = false;
  Vec3 lambert_channels_{1.0f};
};

}  // namespace torrance
