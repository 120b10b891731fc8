// The transmission of Principled v2 (Blender 4.x/5.x's Transmission Weight) as Cycles 4.2-5.x
// renders it (svm/closure.h's transmission component, closure/bsdf_microfacet.h's GGX glass): one
// rough dielectric closure, reflection and refraction with a Fresnel term per microfacet, weighted
// by Transmission Weight (1 - metallic) (MaterialBsdf; the dielectric and diffuse layers keep
// (1 - metallic)(1 - transmission), principled_v2.h).
//
// With alpha = roughness^2, etap = IOR of the far side / IOR of the viewer's side (ior, or 1 / ior
// seen from inside) and c = wo.h of the microfacet normal h:
//   Fresnel     F(c) = mix(f0, 1, s(c)), s(c) = clamp((F_dielectric(c, etap) - F0(etap)) /
//               (1 - F0(etap)), 0, 1), f0 = clamp(F0(ior) * Specular Tint, 0, 1): Specular Tint
//               tints the reflection at normal incidence; Specular IOR Level does NOT act on this
//               closure (Cycles uses the IOR input as it is). At total internal reflection F = 1.
//   reflection  R = F(c),                     f |cos_i| = R D G2 / (4 cos_o)
//   refraction  T = (1 - F(c)) sqrt(base),    f |cos_i| = T D G2 etap^2 |wo.h| |wi.h| /
//                                                         (cos_o (wo.h + etap wi.h)^2)
//               (the base colour, clamped to [0, 1], tints each crossing by its square root:
//               a ray through a closed object is tinted by the base colour once in and out)
// with the height-correlated G2 = 1 / (1 + L(wo) + L(wi)); refraction as Walter et al. 2007 with
// etap^2 in the numerator (no 1 / etap^2 radiance compression), as rough_dielectric.h. A pair
// whose generalised half vector does not face wo, or that wi does not cross, is evaluated with
// |wo.h| |wi.h| as Cycles does (refraction_pair.h): sampling never draws it, NEE does.
// Multiscatter GGX (the node's default): the whole closure is scaled by 1 + F_ms (1 - E) / E
// with E = E(r, mu_o, etap), E_avg from ggx_glass_tables.h and F_ss = sqrt(base) (Cycles: "the
// transmissive tint makes up most of the colour"; the reflective F_ss when that is black).
// Sampling (Cycles): a visible normal h, then reflection with probability
// P_r = mean(R) / mean(R + T) (RGB means), else refraction; pdf = P_r or (1 - P_r) times the
// visible-normal density of the direction. Below ggx_tables::kDeltaAlpha both are deltas (mirror
// or straight refraction, weight R / P_r or T / (1 - P_r)); with |ior - 1| < 1e-4 the interface
// is invisible (straight through, weight sqrt(base)) unless it has a film (a soap bubble): then
// it reflects as above and what it refracts passes straight through, a delta of weight
// T / (1 - P_r) at the sampled microfacet (Cycles 4.2-5.x: their refraction at |etap - 1| < 1e-4
// is singular, their reflection keeps the film's Fresnel).
//
// The Glass BSDF node of Blender 4.x/5.x (glass_node()): the same closure with Specular Tint 1,
// both R and T tinted by its Color (R = F(c) Color, T = (1 - F(c)) Color, Cycles 4.2-5.x's
// svm_node_closure_bsdf glass case) and F_ss = Color for Multiscatter GGX. With the Beckmann
// distribution (beckmann_): Cycles 4.x/5.x's Beckmann glass, the same closure with Beckmann's D and
// Cycles' rational Lambda in G2 (beckmann.h), no energy compensation, microfacet normals drawn
// from Beckmann's visible normals; the pdf is their exact density (G1 of the exact Lambda, within
// 0.32 % of Cycles' stated one).
// The Refraction BSDF node of Blender 4.x/5.x (refraction_node()): the closure's refraction alone,
// no Fresnel (T = Color; 0 where the microfacet totally reflects), no reflection (P_r = 0), GGX or
// Beckmann: Cycles 4.2-5.x's *_refraction closures with Fresnel NONE.
// Anisotropy (Cycles 5.x, stretch()): the Principled's transmission takes the Principled's stretched
// lobe (its Anisotropic, Rotation and Tangent, principled_v2.h) and the Glass node its Anisotropy,
// Rotation and Tangent mapped as the Glossy node's (GlossyBsdf::lobe_shape); the multiscatter
// tables are then read at (alpha_x alpha_y)^(1/4), and the closure is a delta where alpha_x
// alpha_y is (ggx_shape.h). orient() turns the tangent into the shading frame, whose x and y the
// outward frame keeps.
// Frame as GlassBsdf (glass.h), so that MaterialBsdf holds either: z is the surface's OUTWARD
// normal, wo.z < 0 is a viewer inside. eval() includes |cos_i| (bsdf.h). Thin Wall (Blender 5.x)
// is thin_wall_v2.h's instead. Thin Film (thin_film.h): F(c) = the film's reflectance over etap (its
// IOR / ior seen from inside, as Cycles), scaled towards f0 / F0 per channel as the Principled's
// dielectric layer (tinted_film_fresnel); R and T follow from it as above, and a film at total
// internal reflection reflects all.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/microfacet_lobe.h"

namespace torrance {

class PrincipledGlassV2 {
 public:
  // refracting_ior: the IOR at the path's wavelength with dispersion (dispersion.h; Cycles 5.x),
  // which refracts, shapes the Fresnel curve s(c), the multiscatter scale and the film seen from
  // inside, while f0 stays F0(ior) x Specular Tint; ior itself without.
  PrincipledGlassV2(float roughness, float ior, const Vec3& specular_tint, const Vec3& base_color,
                    bool multiscatter, const ThinFilm& film = ThinFilm{});
  PrincipledGlassV2(float roughness, float ior, const Vec3& specular_tint, const Vec3& base_color,
                    bool multiscatter, const ThinFilm& film, float refracting_ior);

  // Blender 4.x/5.x's Glass BSDF node: color (>= 0) tints reflection and refraction alike.
  static PrincipledGlassV2 glass_node(float roughness, float ior, const Vec3& color, bool multiscatter,
                                      const ThinFilm& film = ThinFilm{}, bool beckmann = false);
  // Blender 4.x/5.x's Refraction BSDF node (color >= 0).
  static PrincipledGlassV2 refraction_node(float roughness, float ior, const Vec3& color, bool beckmann);

  // The microfacets stretched along a tangent, as `shape` (isotropic: nothing changes); the
  // distribution is kept. stretch_as_node: the Glass node's Anisotropy (in [-1, 1]), tangent and
  // Rotation (turns), as the Glossy node's.
  void stretch(const ggx::Shape& shape);
  void stretch_as_node(float anisotropy, const Vec3& tangent, float rotation);
  // An anisotropic lobe's tangent into the shading frame (ggx_shape.h); before eval and sample.
  void orient(const Frame& frame) { lobe_.orient(frame); }
  bool anisotropic() const { return lobe_.shape().anisotropic(); }

  Vec3 eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  bool has_delta() const { return smooth_; }
  // Whether sampling can draw wi from wo: false for a refraction pair no microfacet connects,
  // which eval() and pdf() still value as Cycles (refraction_pair.h).
  bool connects(const Vec3& wo, const Vec3& wi) const;

  // Reflectance R and transmittance T of a microfacet at cos c (viewer's side with etap).
  struct Split {
    Vec3 reflect{0.0f}, transmit{0.0f};
    float p_reflect = 1.0f;  // mean(R) / mean(R + T)
  };
  Split split(float c, float etap) const;
  // The multiscatter scale 1 + F_ms (1 - E) / E for a viewer at cos_o with etap (1 without).
  Vec3 energy_scale(float cos_o, float etap) const;

 private:
  struct Lobe {
    Vec3 f_cos{0.0f};
    float pdf = 0.0f;
  };
  // wo.z > 0 (turned to the viewer's side), etap of that side.
  Lobe evaluate(const Vec3& wo, const Vec3& wi, float etap) const;

  Vec3 f0_, tint_t_;
  Vec3 tint_r_{1.0f};  // the reflection's tint: 1, or the Glass node's Color
  float alpha_, roughness_, ior_;  // roughness_: the tables' (alpha_x alpha_y)^(1/4) when stretched
  bool smooth_, multiscatter_;
  MicrofacetLobe lobe_;     // GGX's or Beckmann's microfacets (alpha_, or stretched)
  bool reflective_ = true;  // false: the Refraction node (no Fresnel, no reflection)
  bool straight_;   // |ior - 1| < 1e-4: refraction passes straight through (a delta)
  bool invisible_;  // ... and without a film nothing reflects: the interface is not there
  ThinFilm film_, film_inside_;  // the film seen from outside and from inside (IOR / ior)
};

}  // namespace torrance
