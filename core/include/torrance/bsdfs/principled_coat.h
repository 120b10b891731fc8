// The Principled BSDF's coat lobe, one class per Blender generation, each with eval, pdf and sample
// side by side, in the shading frame (z = the closure's normal after valid_shading_normal, wo.z >
// 0; Cycles' coat normal defaults to the same). Material::coat_* carry the inputs (bsdf.h).
//
// ClearcoatV1: Cycles 3.4's principled clearcoat closure (svm/closure.h, bsdf_microfacet.h), added
// on top of the other lobes (nothing under it is darkened):
//   f cos = w F(wi.h) D1(h) G1(wo) G1(wi) / (4 wo.z),  w = 0.25 Clearcoat,
//   F the exact dielectric Fresnel of IOR 1.5 (cspec0 0.04 = its F0), D1 the GTR1 ("Berry")
//   distribution with a = Clearcoat Roughness^2 (clamped to 1; 1/pi at a = 1):
//       D1 = (a^2 - 1) / (pi ln(a^2) (1 + (a^2 - 1) (n.h)^2)),
//   and G1 the separable Smith masking of GGX with the fixed alpha 0.25.
//   Cycles samples it by GGX's visible normals of alpha a but states (for MIS and the sample
//   weight) the density pdf = G1(wo) D1(h) / (4 wo.z): not the density it draws from. Torrance
//   does the same, so that its images carry the same estimator (and bias) as Cycles'; pdf() is
//   the stated density, sampling_pdf() the true one (what the tests check sample() against).
//   Below a = ggx::kDeltaAlpha (Cycles 3.4's alpha^2 <= 1e-7) the lobe is a mirror of
//   reflectance w F(wo.z). The lobe choice weighs it as Cycles' closure sample weight, w F(wo.z).
//
// CoatV2: Cycles 4.x/5.x's Principled coat (svm/closure.h): a GGX layer (alpha = Coat
// Roughness^2, height-correlated Smith G2, sampled by visible normals) of weight w = Coat Weight
// with the exact dielectric Fresnel F of Coat IOR (>= 1). What it does to the layers under it
// (their base_weight) depends on the Cycles generation (Material::coat_layering), mu the cosine
// of wo to the coat's normal, A its albedo estimate and tint^d the Coat Tint over the path
// d = 1 / cos_t through a coat of unit thickness (cos_t: wo refracted into the coat):
//   Cycles4_2  no energy compensation; A = F(mu) (Cycles' estimate for its plain dielectric
//              Fresnel: the smooth surface's, whatever the roughness, so that a rough coat seen
//              at grazing angles still takes nearly all of the base);
//              base_weight = clamp(1 - w A, 0, 1) mix(1, tint^d, w).
//   Cycles4_5  energy-compensated as the other GGX layers, scale k = 1 + F_ms (1 - E) / E
//              (principled_v2.h's multiscatter, F_ss the mean dielectric Fresnel of Coat IOR);
//              A = k E mix(F0, 1, S(r, mu, ior)) (ggx_tables.h); base_weight as Cycles4_2's.
//   Cycles5_1  the lobe compensated as Cycles4_5's, but A = mix(F0, 1, S) without k and the
//              tint inside the layering, per channel:
//              base_weight = clamp(1 - w (1 - tint^d (1 - A)), 0, 1).
// Below ggx_tables::kDeltaAlpha the coat is a mirror of reflectance scale F(wo.z).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/util/math.h"

namespace torrance {

// Kulla & Conty's multiple-scattering compensation shared by Principled v2's GGX layers.
namespace multiscatter {
// Kulla & Conty's fit of the cosine-weighted mean dielectric Fresnel, integral 2 mu F(mu, eta) dmu.
float mean_dielectric_fresnel(float eta);
// The albedo scaling of a GGX layer whose mean Fresnel is fss: 1 + F_ms (1 - E) / E.
Vec3 scale(const Vec3& fss, float e, float e_avg);
}  // namespace multiscatter

class ClearcoatV1 {
 public:
  ClearcoatV1() = default;
  ClearcoatV1(float clearcoat, float roughness);

  bool active() const { return weight_ > 0.0f; }
  bool is_delta() const;
  // Cycles' sample weight of the closure: w F(wo.z).
  float estimate(float cos_o) const;
  float eval(const Vec3& wo, const Vec3& wi) const;  // f cos (grey)
  float pdf(const Vec3& wo, const Vec3& wi) const;   // the density Cycles states (see above)
  float sampling_pdf(const Vec3& wo, const Vec3& wi) const;  // the density sample() draws from
  Vec3 sample(const Vec3& wo, const Vec2& u) const;  // a direction (possibly below the horizon)
  float mirror_reflectance(float cos_o) const { return estimate(cos_o); }

 private:
  float weight_ = 0.0f, alpha_ = 0.0f;
};

class CoatV2 {
 public:
  CoatV2() = default;
  CoatV2(float weight, float roughness, float ior, const Vec3& tint,
         CoatLayering layering = CoatLayering::Cycles4_5);
  explicit CoatV2(const Material& m)
      : CoatV2(m.coat_weight, m.coat_roughness, m.coat_ior, m.coat_tint, m.coat_layering) {}

  bool active() const { return weight_ > 0.0f; }
  bool reflects() const { return active() && eta_ > 1.0f; }
  bool is_delta() const;
  float alpha() const { return alpha_; }
  float weight() const { return weight_; }

  // What depends on wo alone.
  struct Terms {
    float scale = 0.0f;     // weight x the compensation: the lobe's factor
    float albedo = 0.0f;    // w A: the coat's own albedo estimate (Cycles' bsdf_albedo)
    Vec3 base_weight{1.0f};  // what the layers under the coat keep
  };
  Terms terms(float cos_o) const;

  float eval(const Terms& t, const Vec3& wo, const Vec3& wi) const;  // f cos (grey)
  float pdf(const Vec3& wo, const Vec3& wi) const;
  Vec3 sample(const Vec3& wo, const Vec2& u) const;
  float mirror_reflectance(const Terms& t, float cos_o) const;

 private:
  float weight_ = 0.0f, roughness_ = 0.0f, alpha_ = 0.0f, eta_ = 1.0f, fss_ = 0.0f;
  Vec3 tint_{1.0f};
  bool tinted_ = false;
  CoatLayering layering_ = CoatLayering::Cycles4_5;
  Vec3 through_coat(float cos_o) const;  // tint^d
};

}  // namespace torrance
