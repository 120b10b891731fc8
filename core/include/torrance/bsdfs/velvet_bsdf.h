// The Velvet BSDF node (Blender 3.x) and the Sheen BSDF node's Ashikhmin distribution (4.x) as
// Cycles renders them (closure/bsdf_ashikhmin_velvet.h, unchanged from 3.4 to 5.x): Ashikhmin's
// velvet, an inverted-Gaussian distribution of microfibre normals with a clamped shadowing term,
//
//   f cos = colour * D(h) G / (4 cos_o),
//   D = exp(-cot^2(h) / sigma^2) / (pi sigma^2 sin^4(h)),
//   G = min(1, 2 (n.h / |wo.h|) cos_o, 2 (n.h / |wo.h|) cos_i)   (n.h / |wo.h| at least 1e-5),
//
// sigma = Sigma (3.x) or Roughness (4.x) clamped to [0, 1], then at least 0.01; h = normalize(wo + wi),
// nothing where |n.h| >= 1 - 1e-5 or |wo.h| <= 1e-5. Sampled uniformly over the hemisphere (pdf
// 1 / 2 pi), as Cycles. Everything it reflects is "diffuse" (Cycles' LABEL_DIFFUSE). See bsdf.h
// for the conventions (eval includes the cosine).
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

class VelvetBsdf {
 public:
  VelvetBsdf(const Vec3& color, float sigma);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  // What a mixture samples it by: its colour's luminance.
  float sampling_albedo() const { return luminance(color_); }

 private:
  Vec3 color_;
  float inv_sigma2_;
};

}  // namespace torrance
