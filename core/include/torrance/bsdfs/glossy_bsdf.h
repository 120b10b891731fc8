// The Glossy BSDF node (distribution GGX) as Cycles 3.4 renders it (closure/bsdf_microfacet.h
// with no Fresnel), and 3.4's Anisotropic BSDF (4.x: the Glossy BSDF's Anisotropy): a pure GGX
// reflection lobe whose colour is a plain multiplier,
//
//   f cos = colour * D(h) G1(wo) G1(wi) / (4 cos_o),   alpha = Roughness^2,
//
// with the separable exact Smith G of microfacet.h. Anisotropy a (clamped to +-0.99, as Cycles)
// stretches the lobe along the tangent: alpha_x = alpha (1 - a), alpha_y = alpha / (1 - a) for
// a >= 0, alpha_x = alpha / (1 + a), alpha_y = alpha (1 + a) below, each at most 1; alpha_x lies
// along the tangent made perpendicular to the normal (orient(): the world tangent into the
// shading frame). Where alpha_x alpha_y is below ggx::kDeltaAlpha^2 (Cycles' 1e-7) it is a mirror
// (a delta lobe of reflectance colour). Sampled by visible normals; all "glossy" for the light
// passes. See bsdf.h for the conventions (eval includes the cosine).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/microfacet.h"

namespace torrance {

class GlossyBsdf {
 public:
  // tangent: the world direction alpha_x lies along before the node's Rotation (turns about the
  // normal, counter-clockwise seen from its side, as Cycles' rotate_around_axis); zero, or with
  // anisotropy 0, the lobe is isotropic.
  GlossyBsdf(const Vec3& color, float roughness, float anisotropy = 0.0f, const Vec3& tangent = Vec3(0.0f),
             float rotation = 0.0f);

  // The lobe's axes in the shading frame the integrator evaluates it in: the tangent projected
  // onto the frame's plane (a tangent along the normal, or none: the frame's own x), turned by
  // the rotation.
  void orient(const Frame& frame);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;

  bool has_delta() const {
    return anisotropic_ ? alpha_x_ * alpha_y_ <= ggx::kDeltaAlpha * ggx::kDeltaAlpha : alpha_x_ < ggx::kDeltaAlpha;
  }
  bool anisotropic() const { return anisotropic_; }
  // What a mixture samples it by: its colour's luminance.
  float sampling_albedo() const { return luminance(color_); }

 private:
  // From the shading frame into the lobe's (x along the tangent) and back: a turn about z.
  Vec3 to_lobe(const Vec3& w) const { return Vec3(cos_ * w.x + sin_ * w.y, -sin_ * w.x + cos_ * w.y, w.z); }
  Vec3 from_lobe(const Vec3& w) const { return Vec3(cos_ * w.x - sin_ * w.y, sin_ * w.x + cos_ * w.y, w.z); }
  float reflected_pdf(const Vec3& wo, const Vec3& h) const;  // in the lobe's frame

  Vec3 color_;
  float alpha_x_, alpha_y_;  // equal unless anisotropic_
  bool anisotropic_ = false;
  Vec3 tangent_{0.0f};       // world
  float rotation_ = 0.0f;    // radians
  float cos_ = 1.0f, sin_ = 0.0f;  // the tangent's direction in the shading frame
};

}  // namespace torrance
