// The Principled Hair BSDF's Huang model (Blender 4.0+; Huang, Hullin and Hanika 2022, "A
// Microfacet-based Hair Scattering Model"), as Cycles 4.2 and 5.3 render it far from the camera
// (closure/bsdf_principled_hair_huang.h; 5.3 integrates over the hit offset where 4.2 integrates
// over the ellipse's parameter, the same integral).
//
// The fibre is a dielectric cylinder of elliptical cross-section (minor / major axis = b <= 1,
// the major axis 1) whose surface is a GGX microsurface of alpha = Roughness, its normals tilted
// along the strand by the cuticle angle (the node's Offset, negated as Cycles does). In the
// strand's frame (y along the strand; x, z across it, x the ellipse's major axis or, for a round
// fibre, the direction across the view) a point of the cross-section is p(g) = (sin g, b cos g),
// its outward normal of azimuth atan2(b sin g, cos g). Light meets the fibre at an offset h
// across the view (uniform over the projected width 2r: far field) and leaves as
//   R    reflection off the first microfacet (the node's Reflection weight),
//   TT   refraction in, absorption exp(-sigma l / cos theta_t) along the chord l, refraction out
//        (Transmission weight),
//   TRT  in, one internal reflection, out (Secondary Reflection weight),
//   TRRT+ the rest as a geometric series of the attenuations met so far, spread as Chiang's
//        TRT+ lobe (longitudinal variance 4 alpha, uniform in azimuth).
// Each interface's transmission is scaled by 1 / E, E the directional albedo of GGX glass
// (ggx_glass_tables.h, Cycles' ggx_glass_E), so that a rough fibre keeps the energy a single
// scattering microsurface loses.
//
//   eval(wo, wi): the average over h of those paths from wo into wi, divided by the projected
//        width and cos theta_o (Cycles' eval; it includes the cosine). R by Simpson's rule over h;
//        TT, TRT and the rest at the same nodes, each with one microfacet normal drawn from
//        those visible (a Monte Carlo estimate, as Cycles).
//   sample(wo): h uniform, a visible microfacet at each interface, the path chosen with
//        probability its energy (channel average) over the four paths' total; weight = the
//        chosen path's energy over that probability (Cycles' estimator).
//   pdf: 1, as Cycles (its sample's weight already holds the density: kSampleIsOwnEval); MIS
//        weights stay a partition of unity because eval and pdf are deterministic functions of
//        (wo, wi) (their random numbers are a hash of the directions, microsurface_walk.h).
// eval and sample estimate the same R, TT and TRT: the tests compare the sample weights gathered
// per direction bin with eval integrated over the bin. Not the paths beyond TRT, which Cycles
// estimates differently in each, and which we keep as it does: eval sums T1 R2^2 (a geometric
// series of the first two interfaces' T and R) at its nodes uniform in the parameter g of the
// cross-section where R, TT and TRT are uniform in h, and spreads it by Chiang's lobe; sample
// takes T1 R2 R3 of the path it drew. A clear fibre of Roughness 0.3 seen at 30 degrees: sample's
// albedo 1.01, eval's 1.62 (its R, TT, TRT 0.82 of it; the rest 0.81 against sample's 0.19).
// eval leaves them out where Secondary Reflection is 0, sample keeps them; with every weight 0
// there is no closure (Cycles').
//
// Where |h| >= r (an elliptical fibre seen across its minor axis is narrower than the round tube
// that the ray met) Cycles turns the closure transparent: sample() passes the ray straight on
// (a delta sample of weight 1, BsdfSample::straight_through) and eval is 0. The path tracer takes
// that pass as Cycles takes its Transparent closure (pass_sheet, as a smooth thin wall's): no
// bounce, and a light the ray then meets is MIS-weighted against NEE at the vertex before. Taken
// as a delta bounce instead (MIS weight 1), a sun met through the gap while shadow rays stop at
// the strand (Cycles' too: a strand's shadow transparency is baked without a view, where this
// closure never passes) was a firefly of thousands times the pixel (issue 38).
//
// Not rendered: Cycles' near field (a strand wider than half a pixel seen by a camera ray,
// where Cycles integrates only over the pixel's part of the strand and samples the hit's own h:
// the pixel's mean is the same, its texture across the strand is not) and the curves' normal
// attribute (the ellipse's major axis is Cycles' fallback without one: make_orthonormals of the
// strand's direction). Directions are in the shading frame (z = N, bsdf.h); the strand's
// direction is given in world space and turned by orient().
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

// The node's inputs, reduced as Cycles' svm_node_closure_bsdf reduces them for Huang's model.
struct HuangHairParams {
  Vec3 sigma{0.0f};        // absorption coefficient (per unit of the major radius)
  float roughness = 0.3f;  // GGX alpha (Roughness, clamped to [0.001, 1])
  float ior = 1.55f;
  float offset = 0.0349066f;   // the node's Offset (radians)
  float aspect_ratio = 0.85f;  // minor / major axis (above 1: the axes swapped)
  Vec3 lobe_weights{1.0f};     // Reflection, Transmission, Secondary Reflection
  // The paths beyond TRT (Cycles' always; false: the tests' model of R, TT and TRT alone, whose
  // eval and sample agree).
  bool beyond_trt = true;
  // eval's Simpson nodes per Cycles' (1: its spacing of 0.7 alpha in h for R, 0.8 alpha for the
  // rest; the tests' finer quadrature shows eval converging to what sample draws).
  float quadrature_density = 1.0f;
};

class HuangHairBsdf {
 public:
  static constexpr bool kSampleIsOwnEval = true;

  // tangent: the strand's world direction; on_curve: a hit on a curve (Cycles aligns an ellipse
  // with the curve; on a mesh the frame follows the view and only the aspect remains);
  // curve_normal: the curve's normal attribute there (0: none), the major axis's direction.
  HuangHairBsdf(const HuangHairParams& params, const Vec3& tangent, bool on_curve,
                const Vec3& curve_normal = Vec3(0.0f));
  void orient(const Frame& frame);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  // What a mixture samples it by: the colour a round, smooth fibre of this sigma scatters (the
  // sum of its paths' geometric series), seen head-on.
  float sampling_albedo() const;
  // Whether sample() may pass rays straight on (an ellipse on a curve: Cycles' transparency).
  bool may_pass() const { return b_ != 1.0f && on_curve_; }

 private:
  struct View;  // wo in the strand's frame
  View at(const Vec3& wo) const;
  Vec3 eval_reflection(const View& v, const Vec3& wi, float h_lo, float h_hi) const;
  Vec3 eval_inside(const View& v, const Vec3& wi, float h_lo, float h_hi, uint32_t seed) const;
  // 1 / E of GGX glass at the cosine mu between the ray and the mesonormal, relative IOR eta.
  float energy_scale(float mu, float eta) const;

  Vec3 sigma_;
  float alpha_, eta_, tilt_, b_, node_spacing_;  // node_spacing_: alpha / quadrature_density
  Vec3 weights_;                                 // R, TT, TRT
  bool on_curve_, beyond_trt_;
  Vec3 tangent_, major_;  // in the shading frame (orient), unit
  Vec3 world_tangent_, world_major_;
};

}  // namespace torrance
