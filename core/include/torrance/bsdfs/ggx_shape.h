// The shape of a GGX reflection lobe in the shading frame (z = normal): one alpha (isotropic), or
// alpha_x along a tangent and alpha_y across it (anisotropic, as Cycles' microfacet closures with a
// tangent T). D, Smith's G1 and Lambda, and visible-normal sampling of either, so that a BSDF
// asks its lobe the same questions whether or not it is anisotropic; the isotropic answers are
// microfacet.h's isotropic functions, bit for bit.
//
// An anisotropic shape knows its tangent as a world direction and a rotation (radians, about the
// normal, counter-clockwise seen from its side as Cycles' rotate_around_axis) until orient() turns
// it into the frame the integrator evaluates in: the tangent projected onto the frame's plane (a
// tangent along the normal: the frame's own x), then turned. Directions are then taken into the
// lobe's frame (x along the tangent) by a turn about z. D and G1 are even in the lobe's y, so the
// frame's handedness does not matter.
#pragma once

#include "torrance/bsdfs/microfacet.h"

namespace torrance::ggx {

class Shape {
 public:
  Shape() = default;
  explicit Shape(float alpha) : alpha_x_(alpha), alpha_y_(alpha) {}
  // alpha_x along `tangent` (world) turned by `rotation` radians; isotropic (alpha_x) when
  // alpha_x == alpha_y or the tangent is zero or not finite.
  Shape(float alpha_x, float alpha_y, const Vec3& tangent, float rotation) : alpha_x_(alpha_x), alpha_y_(alpha_x) {
    if (alpha_x == alpha_y || !is_finite(tangent) || !(glm::dot(tangent, tangent) > 0.0f)) return;
    anisotropic_ = true;
    alpha_y_ = alpha_y;
    tangent_ = tangent;
    rotation_ = std::isfinite(rotation) ? rotation : 0.0f;
  }

  // The tangent into `frame` (see above); nothing for an isotropic shape.
  void orient(const Frame& frame) {
    if (!anisotropic_) return;
    const Vec3 t = frame.to_local(tangent_);
    float c = 1.0f, s = 0.0f;
    if (const float len = std::sqrt(t.x * t.x + t.y * t.y); len > 1e-6f) c = t.x / len, s = t.y / len;
    const float cr = std::cos(rotation_), sr = std::sin(rotation_);
    cos_ = c * cr - s * sr;
    sin_ = s * cr + c * sr;
  }

  bool anisotropic() const { return anisotropic_; }
  float alpha_x() const { return alpha_x_; }
  float alpha_y() const { return alpha_y_; }
  // A perfect mirror below `threshold` (an alpha): alpha < threshold, or alpha_x alpha_y <=
  // threshold^2 when anisotropic (Cycles' test on the product).
  bool is_delta(float threshold) const {
    return anisotropic_ ? alpha_x_ * alpha_y_ <= threshold * threshold : alpha_x_ < threshold;
  }

  float D(const Vec3& h) const {
    return anisotropic_ ? D_aniso(to_lobe(h), alpha_x_, alpha_y_) : ggx::D(h, alpha_x_);
  }
  float G1(const Vec3& w) const {
    return anisotropic_ ? smith_G1_aniso(to_lobe(w), alpha_x_, alpha_y_) : smith_G1(w.z, alpha_x_);
  }
  // Smith's Lambda of w (w.z > 0): G1 = 1 / (1 + Lambda).
  float lambda(const Vec3& w) const {
    if (!anisotropic_) return smith_lambda(w.z, alpha_x_);
    if (w.z <= 0.0f) return 0.0f;
    const Vec3 l = to_lobe(w);
    const float s = alpha_x_ * alpha_x_ * l.x * l.x + alpha_y_ * alpha_y_ * l.y * l.y;
    return 0.5f * (std::sqrt(1.0f + s / (l.z * l.z)) - 1.0f);
  }
  // A microfacet normal visible from wo (wo.z > 0); density G1(wo) max(0, wo.h) D(h) / wo.z.
  Vec3 sample_visible_normal(const Vec3& wo, const Vec2& u) const {
    if (!anisotropic_) return ggx::sample_visible_normal(wo, alpha_x_, u);
    return from_lobe(sample_visible_normal_aniso(to_lobe(wo), alpha_x_, alpha_y_, u));
  }
  // A reflection lobe sampled by visible normals: the density of its reflected directions,
  // G1(wo) D(h) / (4 wo.z) (0 unless both lie above the surface), and a direction drawn from it
  // (wo.z > 0; it may lie below the surface).
  float reflection_pdf(const Vec3& wo, const Vec3& wi) const {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    Vec3 h;
    if (!reflection_half(wo, wi, h)) return 0.0f;
    return G1(wo) * D(h) / (4.0f * wo.z);
  }
  Vec3 sample_reflection(const Vec3& wo, const Vec2& u) const { return reflect(wo, sample_visible_normal(wo, u)); }

  // A direction of the shading frame into the lobe's (x along the turned tangent) and back; the
  // identity for an isotropic shape.
  Vec3 to_lobe(const Vec3& w) const { return Vec3(cos_ * w.x + sin_ * w.y, -sin_ * w.x + cos_ * w.y, w.z); }
  Vec3 from_lobe(const Vec3& w) const { return Vec3(cos_ * w.x - sin_ * w.y, sin_ * w.x + cos_ * w.y, w.z); }

 private:
  float alpha_x_ = 0.0f, alpha_y_ = 0.0f;  // equal unless anisotropic_
  bool anisotropic_ = false;
  Vec3 tangent_{0.0f};             // world
  float rotation_ = 0.0f;          // radians
  float cos_ = 1.0f, sin_ = 0.0f;  // the turned tangent's direction in the shading frame
};

}  // namespace torrance::ggx
