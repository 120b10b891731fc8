// Glass as Cycles 3.4 renders Blender's Glass BSDF node and the Principled BSDF's Transmission:
// not one rough dielectric with a Fresnel term per microfacet (RoughDielectricBsdf, Walter et al.
// 2007), but Cycles 3.4's pair of closures split by the Fresnel reflectance of the MACRO normal,
// F = F_dielectric(|n.wo|, etap) (svm/closure.h, bsdf_microfacet.h):
//
//   reflection  weight F         * reflect_color,  GGX, alpha_r:  D G / (4 |cos_o|)  (no Fresnel inside)
//   refraction  weight max(1e-4, 1 - F) * refract_color,  GGX, alpha_t, Walter's BTDF without Fresnel:
//       f |cos_i| = G1(wo) G1(wi) D(h) etap^2 |wo.h| |wi.h| / (|cos_o| (wo.h + etap wi.h)^2)
//
// with separable Smith G, alpha = roughness^2, etap = IOR of wi's side / IOR of wo's side. The
// Principled BSDF uses reflect_color 1 and refract_color = base colour, the refraction roughness
// 1 - (1 - r)(1 - transmission roughness) (Cycles 3.4 with GGX), and tints the reflection by its
// Specular Tint (tint_reflection: Cycles' GGX_FRESNEL closure, its colour per microfacet
// fresnel_interpolated(cspec0, wi.h, etap) with cspec0 = base colour x tint + 1 - tint); the
// Glass node tints both lobes and uses one roughness. The energy is therefore not exactly
// conserved for rough glass (a refracting microfacet whose own Fresnel would reflect still
// refracts; one at total internal reflection loses its sample), exactly as in Cycles 3.4; smooth
// glass conserves it.
//
// Frame and sides as RoughDielectricBsdf: z is the surface's OUTWARD normal, a direction with
// z > 0 is outside (IOR 1), z < 0 inside (IOR `ior`); reflection keeps wi on wo's side.
// Sampling: a lobe with probability proportional to its weight's luminance, then a visible normal
// of that lobe's GGX seen from wo; a refraction through a microfacet at total internal reflection
// gives no sample (Cycles too). Below ggx::kDeltaAlpha a lobe is a delta (mirror / straight
// refraction); with |ior - 1| < 1e-4 the interface is invisible (straight through, weight refract_color)
// unless it has a film (below).
// eval() includes |cos_i| (see bsdf.h); delta lobes have no eval or pdf.
//
// Beckmann (the Glass BSDF node's default distribution in Blender 3.4): the same two closures
// with Cycles' Beckmann D and its rational approximation of Smith's G1 (beckmann.h); its
// microfacet normals are sampled in proportion to D(h) cos(h)
// (not visible normals: a different estimator of the same BSDF).
//
// refraction_only: the Refraction BSDF node's one closure (refraction_bsdf.h): no reflection
// lobe and no Fresnel, the refraction lobe weighted by refract_color alone.
//
// Thin Film (the Glass BSDF of Blender 5.x, thin_film.h): F becomes the film's colour over etap
// (its IOR / ior seen from inside, as Cycles), the lobes weighted F reflect_color and
// max(1e-4, 1 - F) refract_color per channel (Cycles 5.x applies the film per microfacet: the
// same for smooth glass). At IOR 1 the film still reflects (a soap bubble; Cycles too), the rest
// passing straight through. A film flagged 4.x (ThinFilm::cycles5 false) is ignored: Cycles 4.x's
// Glass BSDF has none.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/microfacet.h"

namespace torrance {

class GlassBsdf {
 public:
  GlassBsdf(float reflect_roughness, float refract_roughness, float ior, const Vec3& reflect_color,
            const Vec3& refract_color, bool beckmann = false, bool refraction_only = false,
            const ThinFilm& film = ThinFilm{});

  Vec3 eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  // Whether sampling can draw wi from wo: false for a refraction pair no microfacet connects,
  // which eval() and pdf() still value as Cycles (refraction_pair.h).
  bool connects(const Vec3& wo, const Vec3& wi) const;

  // The macro Fresnel reflectance for wo (the weight of the reflection closure).
  float fresnel(const Vec3& wo) const;
  // The reflection coloured per microfacet as Cycles 3.x's *_FRESNEL closures (above); cspec0
  // clamped to [0, 1], white (the default) leaves it untinted.
  void tint_reflection(const Vec3& cspec0);
  bool has_delta() const { return reflect_delta_ || refract_delta_; }

 private:
  struct Weights {
    Vec3 reflect{0.0f}, refract{0.0f};
    float p_reflect = 0.0f;  // the probability of sampling the reflection lobe
    float etap = 1.0f;       // IOR of the far side / IOR of wo's side
  };
  Weights weights(const Vec3& wo) const;
  // f |cos_i| and pdf of one lobe, for wo and wi turned to wo.z > 0.
  struct Lobe {
    float f_cos = 0.0f, pdf = 0.0f;
    float o_h = 0.0f;  // |wo.h| of the microfacet (reflection: also wi.h)
  };
  Lobe reflection(const Vec3& wo, const Vec3& wi) const;
  // tint_reflection's colour of a reflection through a microfacet at wi.h = cos_ih.
  Vec3 reflection_tint(float cos_ih, float etap) const;
  Lobe refraction(const Vec3& wo, const Vec3& wi, float etap) const;
  // The microfacet distribution (GGX or Beckmann) for wo.z > 0: D, Smith G1, a sampled normal
  // and its density (o_h = |wo.h|: GGX's visible normals; Cycles takes it unsigned).
  float D(const Vec3& h, float alpha) const;
  float G1(float cos_theta, float alpha) const;
  Vec3 sample_normal(const Vec3& wo, float alpha, const Vec2& u) const;
  float normal_pdf(const Vec3& wo, const Vec3& h, float o_h, float alpha) const;

  Vec3 reflect_color_, refract_color_;
  Vec3 cspec0_{1.0f};
  float tint_f0_ = 0.0f;  // F_dielectric(1, ior), the same from either side
  bool tinted_ = false;
  float alpha_r_, alpha_t_, eta_;
  bool reflect_delta_, refract_delta_, invisible_, beckmann_, refraction_only_;
  ThinFilm film_, film_inside_;  // the film seen from outside and from inside (IOR / ior)
};

}  // namespace torrance
