// Blender 3.x's Multiscatter GGX reflection as Cycles 3.4 renders it (its "multi GGX" closures):
// light walks on a GGX microsurface of uniformly distributed heights until it leaves it
// (Heitz, Hanika, d'Eon and Dachsbacher 2016, "Multiple-Scattering Microfacet BSDFs with the
// Smith Model"), so that a white metal keeps nearly all of its energy (single-scattering GGX
// loses up to 70 % of it at roughness 1).
//
// The walk. A ray of direction w (downwards at first) meets the surface at a height drawn from
// the Smith height model: with C1(h) = (h + 1) / 2 and Lambda(w) signed (Lambda(w) for w.z > 0,
// -1 - Lambda(-w) below), an upward ray leaves it with probability G1(w, h) = C1(h)^Lambda(w).
// It reflects off a normal drawn from the normals visible from -w, and goes on, at most ten
// times. Cycles 3.4 puts an upward ray that does not leave at the top of the surface (h = 1)
// rather than at a height drawn by Heitz's formula: so does this walk (HeightStep below).
//
//   eval     an unbiased but noisy estimate of f cos (the Cycles estimator): the single scattering
//            D G2 / (4 cos) with the height-correlated G2 = 1 / (1 + Lambda(wo) + Lambda(wi)),
//            exactly, plus, at every vertex of a walk started from the shallower of the two
//            directions, the chance that it scatters towards the other one and leaves the surface
//            (times cos_shallow / cos_other when the directions were swapped, by reciprocity).
//   sample   the walk itself from wo: the direction it leaves by, its weight the product of the
//            reflectances met (0 when it does not leave within ten bounces).
//   pdf      the walk's density is unknown: as Cycles, pdf is an estimate that MIS uses, the
//            visible-normal single-scattering density weighted by the single-scattering albedo
//            E(r, wo.z) (ggx_tables.h) plus the cosine density weighted by 1 - E. sample()
//            returns it too; its weight is NOT eval / pdf, so a mixture must count a sample as
//            its own eval (mixture_bsdf.h's kSampleIsOwnEval; MIS weights stay a partition of
//            unity, so the sum stays unbiased).
//
// Reflectance per bounce (Reflectance): the Glossy node's colour c (Cycles multiplies the walk by
// c at every bounce but the first, whose c the closure's weight carries), or Principled v1's
// Fresnel F = cspec0 (1 - F_H) + F_H of the facet (Cycles' "fresnel" variant). Cycles' estimators
// weigh these differently, and so do these: eval starts from F of the single-scattering half
// vector and weighs its k-th extra bounce by the square of what the walk met so far (c^(2k), or
// F_ss^2 times the walk's F's squared), sample by the product of what it met (c^k). For c = 1
// and F = 1 both are the same model and agree; for coloured closures this is Cycles' own
// inconsistency, kept so that images match (a lamp light sees eval alone).
//
// Random numbers: Cycles draws the walk from a per-shading-point LCG. eval and sample here
// seed theirs from a hash of their arguments (the directions, and the sample's random numbers),
// which differ from sample to sample: deterministic, reproducible renders. Directions are in the
// shading frame; the anisotropic shape's axes come from orient() (ggx_shape.h). Below
// ggx::kDeltaAlpha (Cycles' alpha_x alpha_y < 1e-7) it is a mirror.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/ggx_shape.h"

namespace torrance::microsurface {

// Where a ray that goes up and does not leave meets the surface again: at the top (Cycles 3.4's
// walk, the default) or at the height Heitz et al. draw. Cycles' step makes the walk lose
// reciprocity: its eval, which walks from the shallower direction, then estimates a darker lobe
// than its sample draws (a white lobe of roughness 1 seen from above: 0.85 against 1.00). Heitz's
// step is the model whose eval and sample agree (the core tests check the estimators on it).
enum class HeightStep { Cycles, Heitz };

// The walk's steps, shared by the glossy walk (Walk below) and the glass walk
// (multiscatter_glass_bsdf.h).
constexpr int kMaxBounces = 10;  // Cycles 3.4's

// The walk's random numbers: a counter hashed with a seed taken from the query's arguments.
class Random {
 public:
  explicit Random(uint32_t seed) : seed_(seed) {}
  float next();
  Vec2 next_2d() {
    const float a = next();
    return Vec2(a, next());
  }

 private:
  uint32_t seed_, count_ = 0;
};
uint32_t seed_of(const Vec3& a, const Vec3& b);

// The height model: C1(h) = (h + 1) / 2 on [-1, 1], and G1(w, h) = C1(h)^Lambda(w) for an
// upward w (1 straight up, 0 at and below the horizon).
float c1_of(float h);
float escape(const Vec3& w, float c1, float lambda_w);
// Where a ray of direction w meets the surface again: its C1, height and escape chance in `s`;
// false when it leaves the surface instead.
struct Height {
  float h = 1.0f, c1 = 1.0f, g1 = 0.0f, lambda = 0.0f;
};
bool next_height(const Vec3& w, Height& s, float u, HeightStep step);
// The signed Smith Lambda (Lambda(w) for w.z > 0, -1 - Lambda(-w) below) and D of `shape`, in
// its lobe frame.
float signed_lambda(const ggx::Shape& shape, const Vec3& w);
float facet_density(const ggx::Shape& shape, const Vec3& h);
Vec3 reflect_ray(const Vec3& w, const Vec3& m);

// What one bounce off a facet keeps (see above).
struct Reflectance {
  bool fresnel = false;   // Principled v1's Fresnel (else the colour)
  Vec3 color{1.0f};
  Vec3 cspec0{0.0f};      // Principled v1's F0 colour and its dielectric IOR
  float eta = 1.5f, f0 = 0.04f;
  Vec3 at(float cos_d) const;  // the Fresnel at cos(facet normal, ray); the colour otherwise
};

class Walk {
 public:
  Walk() = default;
  Walk(const ggx::Shape& shape, const Reflectance& reflectance, HeightStep step = HeightStep::Cycles)
      : shape_(shape), reflectance_(reflectance), step_(step) {}

  void orient(const Frame& frame) { shape_.orient(frame); }
  const ggx::Shape& shape() const { return shape_; }
  bool has_delta() const { return shape_.is_delta(ggx::kDeltaAlpha); }

  Vec3 eval(const Vec3& wo, const Vec3& wi) const;  // f cos, estimated
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;  // weight: the walk's throughput

 private:
  float lambda(const Vec3& w) const;  // signed Smith Lambda, lobe frame
  float D(const Vec3& h) const;       // lobe frame
  float phase(const Vec3& w, float lambda_w, const Vec3& out) const;

  ggx::Shape shape_;
  Reflectance reflectance_;
  HeightStep step_ = HeightStep::Cycles;
};

}  // namespace torrance::microsurface
