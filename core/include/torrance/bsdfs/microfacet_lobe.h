// A reflection lobe's microfacets as Cycles evaluates them: GGX (ggx_shape.h, microfacet.h) or
// Beckmann (beckmann.h: its D and Cycles' rational fit of Smith's Lambda), over one ggx::Shape's
// alphas and turn (isotropic, or stretched along a tangent). The Glossy and Metallic BSDF nodes
// ask their lobe here, whichever distribution the node names.
//
// visible_g1 and sample_visible_normal: the normals sampling draws and their masking, which for
// Beckmann uses Smith's exact Lambda (the density drawn; the fit stays within 0.32 % of it).
#pragma once

#include "torrance/bsdfs/ggx_shape.h"

namespace torrance {

class MicrofacetLobe {
 public:
  MicrofacetLobe() = default;
  MicrofacetLobe(const ggx::Shape& shape, bool beckmann) : shape_(shape), beckmann_(beckmann) {}

  void orient(const Frame& frame) { shape_.orient(frame); }
  const ggx::Shape& shape() const { return shape_; }
  bool beckmann() const { return beckmann_; }

  float D(const Vec3& h) const;
  float lambda(const Vec3& w) const;  // w.z > 0
  float G1(const Vec3& w) const;      // GGX: the exact Smith G1; Beckmann: 1 / (1 + lambda)
  float visible_g1(const Vec3& wo) const;
  Vec3 sample_visible_normal(const Vec3& wo, const Vec2& u) const;

  // Reflection by visible normals: the density of the reflected directions (0 unless both lie
  // above the surface) and a direction drawn from it (it may lie below the surface).
  float reflection_pdf(const Vec3& wo, const Vec3& wi) const;
  Vec3 sample_reflection(const Vec3& wo, const Vec2& u) const;

 private:
  ggx::Shape shape_;
  bool beckmann_ = false;
};

}  // namespace torrance
