// A reflection lobe's microfacets as Cycles evaluates them: GGX (ggx_shape.h, microfacet.h),
// Beckmann (beckmann.h: its D and Cycles' rational fit of Smith's Lambda) or Ashikhmin-Shirley
// (ashikhmin_shirley.h), over one ggx::Shape's alphas and turn (isotropic, or stretched along a
// tangent). The Glossy and Metallic BSDF nodes ask their lobe here, whichever distribution the
// node names.
//
// visible_g1 and sample_visible_normal: the normals sampling draws and their masking, which for
// Beckmann uses Smith's exact Lambda (the density drawn; the fit stays within 0.32 % of it).
// D, lambda, G1, visible_g1 and sample_visible_normal are GGX's or Beckmann's: an Ashikhmin-Shirley
// lobe has no Smith masking and answers ashikhmin_shirley_eval instead (is_delta, reflection_pdf
// and sample_reflection serve all three).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/ggx_shape.h"

namespace torrance {

class MicrofacetLobe {
 public:
  MicrofacetLobe() = default;
  MicrofacetLobe(const ggx::Shape& shape, MicrofacetDistribution distribution)
      : shape_(shape), distribution_(distribution) {}

  void orient(const Frame& frame) { shape_.orient(frame); }
  const ggx::Shape& shape() const { return shape_; }
  MicrofacetDistribution distribution() const { return distribution_; }
  bool beckmann() const { return distribution_ == MicrofacetDistribution::Beckmann; }
  bool ashikhmin_shirley() const { return distribution_ == MicrofacetDistribution::AshikhminShirley; }

  // A mirror: GGX and Beckmann below `threshold` (ggx::Shape::is_delta), Ashikhmin-Shirley at
  // its own (both alphas at most 1e-4).
  bool is_delta(float threshold) const;

  float D(const Vec3& h) const;
  float lambda(const Vec3& w) const;  // w.z > 0
  float G1(const Vec3& w) const;      // GGX: the exact Smith G1; Beckmann: 1 / (1 + lambda)
  float visible_g1(const Vec3& wo) const;
  Vec3 sample_visible_normal(const Vec3& wo, const Vec2& u) const;

  // Ashikhmin-Shirley's f cos (colour 1; 0 unless both lie above the surface).
  float ashikhmin_shirley_eval(const Vec3& wo, const Vec3& wi) const;

  // Reflection by visible normals (Ashikhmin-Shirley: by its half vectors): the density of the
  // reflected directions (0 unless both lie above the surface) and a direction drawn from it (it
  // may lie below the surface).
  float reflection_pdf(const Vec3& wo, const Vec3& wi) const;
  Vec3 sample_reflection(const Vec3& wo, const Vec2& u) const;

 private:
  ggx::Shape shape_;
  MicrofacetDistribution distribution_ = MicrofacetDistribution::GGX;
};

}  // namespace torrance
