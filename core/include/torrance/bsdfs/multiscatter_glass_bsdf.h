// Blender 3.x's Multiscatter GGX glass as Cycles 3.4 renders it (its "multi GGX glass" closures):
// the Glass BSDF node with Multiscatter GGX, and Principled v1's transmission with Multiscatter
// GGX above roughness 0.05. Light walks on a GGX microsurface (microsurface_walk.h's heights and
// steps; Heitz, Hanika, d'Eon and Dachsbacher 2016) whose facets are a dielectric interface: at
// each facet it reflects with the facet's Fresnel F(cos, eta) and refracts otherwise, crossing to
// the surface seen from the other side (height h -> -h, eta -> 1 / eta), until it leaves on one
// side or the other. A white glass thus keeps its energy (reflection + transmission = 1 but for
// the walks cut at ten bounces), where the single-scattering pair of closures (glass.h) loses it.
//
// Frame: as GlassBsdf (z the OUTWARD normal, wo.z < 0 inside, `ior` inside); the walk runs in the
// frame turned towards wo, with eta the relative IOR of the far side (1 / ior from inside).
//
//   eval     an estimate of f |cos_i| (Cycles' estimator): the single scattering exactly (the
//            facet's Fresnel, D, and the height-correlated G2 of a reflection, or the
//            transmission's Beta-function G2), plus at every later vertex of a walk started from
//            the shallower direction the chance that it scatters towards the other one and
//            leaves. As Cycles 3.4 (HeightStep::Cycles): the refraction phase without the
//            Jacobian's eta^2 (Cycles' sample has it: its eval and sample differ by eta^2 for
//            transmission), a swapped transmission walked with the unswapped eta, the Principled
//            reflection's first vertex estimated rather than exact.
//   sample   the walk from wo: the direction it leaves by, its weight the product of what it met.
//            As Cycles, a walk that crossed keeps the C1 of its height before the crossing.
//   pdf      an estimate for MIS (the walk's density is unknown): the facet Fresnel of the
//            single-scattering half vector times (E x that lobe's visible-normal density + (1 - E)
//            x |cos_i| / pi), E single-scattering GGX's albedo (ggx_tables.h). sample()
//            returns it; its weight is NOT eval / pdf (kSampleIsOwnEval, mixture_bsdf.h).
//   HeightStep::Heitz: Heitz's model instead (his height step, the crossing's height, the
//            Jacobian, the reversed walk's 1 / eta and eta^2): its eval and sample agree (tests).
//
// Colour: the Glass node's c multiplies every bounce of the eval and every bounce but the first
// of the sample (the closure's weight, c, carries that one). Principled v1 (fresnel): reflecting
// facets keep Cycles' F-interpolated tint cspec0 (1 - F_H) + F_H (cspec0 = base colour x
// Specular Tint + 1 - Specular Tint), refracting ones the base colour; its eval of a transmission
// is the Glass node's with the base colour (Cycles too). Below alpha alpha < 1e-7 (alpha =
// max(r^2, 1e-4)) smooth glass: mirror with probability F, else straight refraction, weight c.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/microsurface_walk.h"

namespace torrance {

class MultiscatterGlassBsdf {
 public:
  static constexpr bool kSampleIsOwnEval = true;

  // The Glass node (colour c).
  MultiscatterGlassBsdf(float roughness, float ior, const Vec3& color,
                        microsurface::HeightStep step = microsurface::HeightStep::Cycles);
  // Principled v1's transmission: base colour and its specular-tinted cspec0.
  static MultiscatterGlassBsdf principled(float roughness, float ior, const Vec3& base_color, float specular_tint,
                                          microsurface::HeightStep step = microsurface::HeightStep::Cycles);

  Vec3 eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;

  bool has_delta() const { return smooth_; }
  float sampling_albedo() const { return luminance(weight_); }

 private:
  struct Turned {  // wo (and wi) in the frame turned towards wo, and the relative IOR there
    Vec3 wo, wi;
    float eta;
  };
  Turned turn(const Vec3& wo, const Vec3& wi) const;
  Vec3 walk_eval(Vec3 a, Vec3 b, float eta, uint32_t seed) const;
  Vec3 walk_sample(const Vec3& a, float eta, const Vec2& u, uint32_t seed, Vec3& out) const;
  float walk_pdf(const Vec3& a, const Vec3& b, float eta) const;
  // Density of scattering from ray direction w (lambda_w its Lambda) towards `out`, which leaves
  // on the walk's side (reflect) or the far side, eta the relative IOR of the far side.
  float phase(const Vec3& w, float lambda_w, const Vec3& out, bool reflect, float eta) const;
  Vec3 tint(const Vec3& w, const Vec3& m, float eta) const;  // Principled's reflecting facet

  ggx::Shape shape_;
  Vec3 weight_{1.0f}, color_{1.0f}, cspec0_{1.0f};  // closure weight, per-bounce colour, tint
  float ior_ = 1.5f, roughness_ = 0.0f;
  bool fresnel_ = false, smooth_ = false;
  microsurface::HeightStep step_ = microsurface::HeightStep::Cycles;
};

}  // namespace torrance
