// Principled BSDF v2, "PRINCIPLED_V2": Blender 4.x's Principled BSDF as Cycles 4.x renders it, for
// the inputs Torrance supports (base colour, metallic, roughness, IOR, Specular IOR Level through
// Material::specular, Specular Tint as a colour, emission, coat, sheen, anisotropy, subsurface
// weight, thin film; transmission below). Five layers, from the top, with alpha = roughness^2 (GGX;
// Anisotropic a in [0, 1] stretches the metal and dielectric lobes along the tangent as Cycles
// 4.x: alpha_x = alpha / s, alpha_y = alpha s, s = sqrt(1 - 0.9 a), ggx_shape.h, and the tables
// below are read at the roughness (alpha_x alpha_y)^(1/4)):
//
//   sheen       principled_sheen.h's SheenV2 (Cycles' microfiber sheen) about its own normal, the
//               closure's leaned towards the coat's by the Coat Weight (View::sheen_normal); the
//               four layers under it are scaled by its keep(wo) = clamp(1 - max_rgb(albedo), 0, 1),
//               as Cycles 4.x's.
//   coat        principled_coat.h's CoatV2 (its own roughness, IOR and normal: the View's
//               coat_normal, bsdf.h); the three layers under it are scaled by its base_weight(wo),
//               as Cycles 4.x darkens and tints them, wo's cosine taken about the coat's normal.
//   metal       weight metallic. GGX with height-correlated Smith G2 = 1 / (1 + L(wo) + L(wi))
//               and the F82-tint Fresnel (Kutz et al., "Novel aspects of the Adobe Standard
//               Material"):  F_m(c) = clamp(F_s(c) - b c (1 - c)^6, 0, 1),
//               F_s(c) = f0 + (1 - f0)(1 - c)^5, f0 = base colour, c = wo.h, and b chosen so that
//               F_m(1/7) = F_s(1/7) * tint (tint = Specular Tint, clamped to [0, 1]):
//               b = F_s(1/7) (1 - tint) 7 / (6/7)^6.
//   dielectric  weight (1 - metallic)(1 - transmission) (Transmission Weight: the glass of
//               principled_glass_v2.h takes (1 - metallic) transmission). The same GGX lobe
//               with F_d(c) = mix(f0 tint, 1, s(c)),
//               s(c) = clamp((F(c, eta) - F0(eta)) / (1 - F0(eta)), 0, 1), F the exact dielectric
//               Fresnel and F0(eta) = ((eta - 1) / (eta + 1))^2. The Specular IOR Level rescales
//               F0: f0 = 2 level F0(ior) = 0.08 specular (Material::specular carries it, see
//               bsdf.h), and eta = ior_from_F0(f0) = (1 + sqrt f0) / (1 - sqrt f0) (1 / that for
//               ior < 1; eta = ior when f0 = F0(ior), i.e. level 0.5). No lobe when eta = 1
//               and no film. Thin Film (thin_film.h): F_d = the film's reflectance over eta,
//               each channel scaled towards f0 tint / F0(eta) as far as it lies from 1 towards
//               F0(eta) (tinted_film_fresnel), and A_d below that at cos_o (Cycles' estimate
//               without its tables); the multiscatter F_ss stays the film-less one (Cycles).
//               Cycles 5.x puts the film over the metal too: F_m = the film over the conductor
//               whose n, k Gulbrandsen's fit gives for (f0, F_m(1/7)), its albedo F_m(cos_o).
//   diffuse     Lambert about the View's diffuse_normal (bsdf.h: Cycles 4.x's diffuse keeps the
//               unchecked normal; Diffuse Roughness above 0, Blender 4.3+: the energy-preserving
//               Oren-Nayar of oren_nayar_eon.h, albedo the base colour in [0, 1]), base colour (1 - metallic)(1 - transmission) w(wo): the
//               light the dielectric layer does not reflect, w = clamp(1 - max_rgb(A_d(wo)), 0, 1), with the dielectric layer's
//               estimated albedo A_d = k mix(f0 tint, 1, S(r, mu_o, eta)) (ggx_tables.h).
//               Subsurface Weight w_s (Material::subsurface): the diffuse keeps base (1 - w_s)
//               and the random walk (subsurface_lobe.h) takes min(base, 1) w_s under the same
//               layer weights (ViewTerms::subsurface), in the channels it walks; the others
//               shade that part as diffuse too (Cycles' fallback). With Thin Wall (Blender
//               5.x) there is no walk: the diffuse keeps min(base, 1) w_s (1 - g) / 2 more and
//               ViewTerms::translucent is min(base, 1) w_s (1 + g) / 2 under the same layer
//               weights (g = Subsurface Anisotropy, each share clamped to [0, 1]), the Lambertian
//               translucency that thin_wall_v2.h renders.
//
// Multiscatter GGX (Material::multiscatter_ggx, the node's default "Multiscatter GGX"): each GGX
// layer is scaled by 1 + F_ms (1 - E) / E (albedo scaling, Kulla & Conty 2017), E = E(r, mu_o)
// and E_avg = E_avg(r) from ggx_tables.h, F_ms = F_ss E_avg / (1 - F_ss (1 - E_avg)) with F_ss
// the layer's cosine-weighted mean Fresnel: metal mix(f0, 1, 1/21) - b / 126 (exact for F_m
// before clamping), dielectric mix(f0 tint, 1, s_ss) with s_ss from Kulla & Conty's fit of
// integral 2 mu F(mu, eta) dmu. The diffuse layer sees k = E (1 + F_ms (1 - E) / E) in A_d
// (k = 1 without multiscatter). With F = 1 the scale is 1 / E: a white metal conserves energy.
//
// Below ggx_tables::kDeltaAlpha (Cycles 4.x's threshold) the GGX layers are a mirror with
// reflectance sum(layer scale F(n.wo)). Like Cycles, the model is not reciprocal (the layer
// weights depend on wo). Sampling: lobe_mixture.h (one GGX lobe for both layers, visible normals).
// See bsdf.h for the conventions (eval includes the cosine).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/lobe_mixture.h"
#include "torrance/bsdfs/metal_fresnel.h"
#include "torrance/bsdfs/oren_nayar_eon.h"
#include "torrance/bsdfs/principled_coat.h"
#include "torrance/bsdfs/principled_sheen.h"

namespace torrance {

class PrincipledV2Bsdf : public lobe_mixture::Queries<PrincipledV2Bsdf> {
 public:
  explicit PrincipledV2Bsdf(const Material& m);

  // The wo-dependent layer weights.
  struct ViewTerms {
    Vec3 metal_scale{0.0f};        // metallic (x the multiscatter scale)
    Vec3 dielectric_scale{0.0f};   // (1 - metallic) (x the multiscatter scale)
    Vec3 dielectric_albedo{0.0f};  // A_d, the estimate the diffuse layer is reduced by
    Vec3 diffuse{0.0f};            // (1 - metallic) base colour w(wo)
    Vec3 subsurface{0.0f};         // the random walk's weight: as diffuse, of its own colour
    Vec3 translucent{0.0f};        // Thin Wall: the subsurface's translucency (thin_wall_v2.h)
    CoatV2::Terms coat;            // the coat's (its base_weight is in the three above)
    SheenBsdf::Lobe sheen;         // the sheen's weight (its albedo), a, b (its keep is in all above)
  };
  // cos_coat, cos_sheen: wo's cosines about the coat's and the sheen's normals (cos_o without
  // normals of their own).
  ViewTerms view_terms(float cos_o, float cos_coat, float cos_sheen) const;
  ViewTerms view_terms(float cos_o, float cos_coat) const { return view_terms(cos_o, cos_coat, cos_o); }
  ViewTerms view_terms(float cos_o) const { return view_terms(cos_o, cos_o, cos_o); }

  // The albedo of each closure Cycles 4.x makes of the material (closure/bsdf.h's bsdf_albedo:
  // the closure's weight, its layering and multiscatter darkening included, times its Fresnel
  // estimate for microfacet closures), as its Denoising Albedo and Diff/Gloss Color passes take
  // them: diffuse; dielectric mix(f0 tint, 1, S); metal mix(f0, 1, S5) (ggx_tables.h); the coat's
  // and the sheen's. `layers`: what the coat and the sheen leave the layers under them (the
  // Transmission Weight's glass, principled_glass_v2.h, takes it too).
  struct ClosureAlbedos {
    Vec3 diffuse{0.0f}, dielectric{0.0f}, metal{0.0f}, coat{0.0f}, sheen{0.0f}, layers{1.0f};
  };
  ClosureAlbedos closure_albedos(float cos_o) const;
  // What Cycles 4.x leaves of material m's emission (Material::emission_under_layers) seen from a
  // view at cos_coat to the coat's normal and cos_sheen to the sheen's: the coat's base_weight
  // times the sheen's keep (1 without them), as the layers under them.
  static Vec3 emission_weight(const Material& m, float cos_coat, float cos_sheen);
  static Vec3 emission_weight(const CoatV2& coat, const SheenV2& sheen, float cos_coat, float cos_sheen);
  float coat_alpha() const { return coat_.alpha(); }

  // What eval, pdf and sample need of wo alone (lobe_mixture.h), prepared once per shading point.
  struct View : lobe_mixture::View {
    using Model = PrincipledV2Bsdf;
    ViewTerms terms;
    float lambda_o = 0.0f;  // the GGX shape's Lambda(wo)
    SheenBsdf::Lobe sheen;  // terms.sheen in wo's frame (no weight without a sheen)
    // The sheen's normal: the closure's leaned towards the coat's by the Coat Weight, as Cycles
    // 4.x/5.x (CoatNormal::sheen_normal; tilted only where a Normal input or Coat Normal sets
    // them apart); the sheen's eval, pdf and sample work about it.
    CoatNormal sheen_normal;
  };
  // coat: the coat's normal (bsdf.h; by default the shading normal).
  View at(const Vec3& wo, const CoatNormal& coat = {}) const;        // with the lobe choice p_spec
  View geometry(const Vec3& wo, const CoatNormal& coat = {}) const;  // without it (p_spec = 1): enough for eval

  LobeEval eval_lobes(const View& v, const Vec3& wi) const;
  using lobe_mixture::Queries<PrincipledV2Bsdf>::eval_lobes;  // pdf, sample, eval: lobe_mixture::Queries

  float alpha() const { return alpha_; }
  float roughness() const { return table_roughness_; }  // what the albedo tables are read at
  const ggx::Shape& shape() const { return shape_; }
  // Anisotropic: the tangent into the shading frame (ggx_shape.h); before at().
  void orient(const Frame& frame) { shape_.orient(frame); }
  bool has_delta() const { return shape_.is_delta(ggx_tables::kDeltaAlpha); }
  Vec3 mirror_reflectance(const Vec3& wo) const;
  float specular_probability(const Vec3& wo) const { return specular_probability(view_terms(wo.z), wo.z); }

  Vec3 metal_fresnel(float cos_ih) const;       // F_m
  Vec3 dielectric_fresnel(float cos_ih) const;  // F_d (0 without a dielectric lobe)
  float eta() const { return eta_; }
  // The IOR the dielectric layer has: the IOR, or as the Specular IOR Level rescales its F0.
  static float dielectric_eta(const Material& m);
  bool has_subsurface() const { return subsurface_color_ != Vec3(0.0f); }
  // The random walk's closure weight for a view at cos_o (Cycles' BSSRDF weight, layers included).
  Vec3 subsurface_weight(float cos_o) const { return view_terms(cos_o).subsurface; }

  // The coat lobe (lobe_mixture.h).
  bool has_coat() const { return coat_.reflects(); }
  float coat_pdf(const lobe_mixture::View& v, const Vec3& wi) const { return lobe_mixture::coat_pdf(coat_, v, wi); }
  Vec3 coat_sample(const lobe_mixture::View& v, const Vec2& u) const { return lobe_mixture::coat_sample(coat_, v, u); }
  bool coat_is_delta() const { return coat_.is_delta(); }
  Vec3 coat_mirror_reflectance(const View& v) const {
    return Vec3(coat_.mirror_reflectance(v.terms.coat, v.coat_normal.cosine(v.wo)));
  }
  const CoatV2& coat() const { return coat_; }

  // The sheen lobe (lobe_mixture.h), chosen first with View::p_sheen.
  float sheen_pdf(const View& v, const Vec3& wi) const {
    const Vec3 w = v.sheen_normal.to_coat(wi);
    return w.z > 0.0f ? v.sheen.density(w) : 0.0f;
  }
  Vec3 sheen_sample(const View& v, const Vec2& u) const { return v.sheen_normal.from_coat(v.sheen.sample(u)); }
  bool has_sheen() const { return sheen_.active(); }

 private:
  float specular_probability(const ViewTerms& v, float cos_o) const;
  Vec3 specular_estimate(const ViewTerms& v, float cos_o) const;  // the GGX layers' albedo, layered
  Vec3 dielectric_albedo(float cos_o) const;  // the dielectric layer's Fresnel estimate (x E k: A_d)

  Vec3 diffuse_color_{0.0f}, subsurface_color_{0.0f};  // the diffuse and walked parts of the base
  Vec3 translucent_color_{0.0f};  // Thin Wall: the translucent part of the base
  EnergyPreservingOrenNayar diffuse_lobe_;  // Diffuse Roughness (Lambert at 0), per unit weight
  F82Tint metal_;  // the metal's Fresnel
  Vec3 metal_fss_, dielectric_f0_, dielectric_fss_;
  float dielectric_weight_ = 1.0f;  // (1 - metallic)(1 - transmission): Transmission Weight's glass is
                                   // principled_glass_v2.h's, which MaterialBsdf adds
  float metallic_, roughness_, alpha_, eta_;
  float table_roughness_;  // the roughness the albedo tables are read at: roughness_ unless anisotropic
  ggx::Shape shape_;       // the metal and dielectric lobes: alpha_, or stretched by Anisotropic
  bool has_dielectric_, multiscatter_;
  CoatV2 coat_;
  SheenV2 sheen_;
  ThinFilm film_;          // Thin Film (inactive: none)
  bool metal_film_ = false;  // Cycles 5.x: the film over the metal, a conductor of index n + ik:
  Vec3 metal_n_{0.0f}, metal_k_{0.0f}, metal_f82_{0.0f};  // (f82: F_m(1/7), R23's F82 fit)
};

}  // namespace torrance
