// The Principled BSDF's sheen, one class per Blender generation, in the shading frame (z = the
// closure's normal, wo.z > 0). Material::sheen_* carry the inputs (bsdf.h).
//
// SheenV1: Cycles 3.4's principled sheen closure (closure/bsdf_principled_sheen.h, svm/closure.h):
//   f cos = sheen colour * (1 - wi.h)^5 * wi.z   (Burley's sheen: no 1/pi),
//   colour = Sheen (1 - metallic)(1 - transmission) mix(1, base / lum(base), Sheen Tint),
//   lum the scene's luminance (Rec. 709: Cycles' linear_rgb_to_gray; 1 for a black base),
// added to the diffuse lobe (Cycles' LABEL_DIFFUSE) and sampled with it by the cosine, as Cycles
// samples it. Left out under Cycles' CLOSURE_WEIGHT_CUTOFF of Sheen or of the diffuse weight.
//
// SheenV2: Cycles 4.x's Principled sheen (4.2-5.x svm/closure.h, its first layer, above the coat):
// sheen_bsdf.h's microfiber lobe of colour Sheen Weight x Sheen Tint and Sheen Roughness, whose
// albedo A(wo) = colour R(wo.z, roughness) every layer under it (coat, metal, specular, diffuse)
// is scaled by, as Cycles' closure_layering_weight: keep(wo) = clamp(1 - max_rgb(A), 0, 1).
#pragma once

#include "torrance/util/math.h"
#include "torrance/bsdfs/sheen_bsdf.h"

namespace torrance {

// Schlick's weight (1 - c)^5, c clamped to [0, 1] (Cycles' schlick_fresnel).
inline float schlick_weight(float c) {
  const float m = 1.0f - clamp01(c);
  return (m * m) * (m * m) * m;
}

class SheenV1 {
 public:
  SheenV1() = default;
  // base: the clamped base colour; diffuse_weight: (1 - metallic)(1 - transmission).
  SheenV1(float sheen, float tint, const Vec3& base, float diffuse_weight);

  bool active() const { return active_; }
  const Vec3& color() const { return color_; }
  // f cos for cos_d = wi.h and cos_i = wi.z (both > 0).
  Vec3 eval(float cos_d, float cos_i) const { return color_ * (schlick_weight(cos_d) * cos_i); }
  // The lobe choice's estimate of its reflectance: the mean colour times Cycles' avg_value
  // (1 - wo.z)^5 wo.z, at least 1 % of the mean colour (Cycles' is 0 at normal incidence, where it
  // samples the world as a light; Torrance leaves a uniform world to the BSDF).
  float estimate(float cos_o) const;

 private:
  Vec3 color_{0.0f};
  bool active_ = false;
};

class SheenV2 {
 public:
  SheenV2() = default;
  SheenV2(float weight, float roughness, const Vec3& tint);

  bool active() const { return active_; }
  // What depends on wo.z alone: the lobe's weight (its albedo A), a and b; keep(A) below.
  SheenBsdf::Lobe terms(float cos_o) const { return lobe_.lobe_at(cos_o); }
  static float keep(const SheenBsdf::Lobe& t) { return clamp01(1.0f - max_component(t.weight)); }

 private:
  SheenBsdf lobe_;
  bool active_ = false;
};

}  // namespace torrance
