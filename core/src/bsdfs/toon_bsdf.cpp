#include "torrance/bsdfs/toon_bsdf.h"

#include "torrance/util/sampling.h"

namespace torrance {
namespace {

float clamped(float x) { return std::isfinite(x) ? clamp01(x) : 0.0f; }

// theta_s, the lit cone's half angle (Cycles' bsdf_toon_get_sample_angle).
float cone_angle(float size, float smooth) { return std::min(size + smooth, kPi * 0.5f); }

}  // namespace

ToonBsdf::ToonBsdf(const Vec3& color, float size, float smooth, bool glossy, bool cycles4)
    : color_(glm::max(color, Vec3(0.0f))),
      size_(clamped(size) * kPi * 0.5f),
      smooth_(clamped(smooth) * kPi * 0.5f),
      glossy_(glossy),
      cycles4_(cycles4) {
  const float theta_s = cone_angle(size_, smooth_);
  // 1 - cos theta = 2 sin^2(theta / 2), exact for small cones.
  const float half_sin = std::sin(0.5f * theta_s);
  one_minus_cos_cone_ = 2.0f * half_sin * half_sin;
  cone_pdf_ = one_minus_cos_cone_ > 0.0f ? 1.0f / cone_solid_angle(one_minus_cos_cone_) : 0.0f;
}

float ToonBsdf::intensity(float angle) const {
  if (angle < size_) return 1.0f;
  if (smooth_ > 0.0f && angle < size_ + smooth_) return 1.0f - (angle - size_) / smooth_;
  return 0.0f;
}

bool ToonBsdf::axis_cosine(const Vec3& wo, const Vec3& wi, float& cos_angle) const {
  if (!(cone_pdf_ > 0.0f) || !(wi.z > 0.0f)) return false;
  if (!glossy_) {
    cos_angle = wi.z;
    return true;
  }
  if (!(wo.z > 0.0f)) return false;
  cos_angle = glm::dot(Vec3(-wo.x, -wo.y, wo.z), wi);
  return true;
}

LobeEval ToonBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  float c;
  if (!axis_cosine(wo, wi, c)) return {};
  const float angle = std::acos(std::min(std::max(c, 0.0f), 1.0f));
  // Nothing at or past the cone's edge, as Cycles: where Size + Smooth pass 90 degrees the cone
  // is the hemisphere about the axis, and the fade's last value must not light what lies beyond.
  if (!(angle < cone_angle(size_, smooth_))) return {};
  const float i = intensity(angle);
  LobeEval f;
  (glossy_ ? f.glossy : f.diffuse) = color_ * (i * cone_pdf_);
  return f;
}

float ToonBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  float c;
  if (!axis_cosine(wo, wi, c)) return 0.0f;
  return 1.0f - c <= one_minus_cos_cone_ ? cone_pdf_ : 0.0f;
}

BsdfSample ToonBsdf::sample(const Vec3& wo, float /*u_lobe*/, const Vec2& u) const {
  if (!(cone_pdf_ > 0.0f) || (glossy_ && !(wo.z > 0.0f))) return {};
  // 1 - cos theta as a share of the cone's, and the azimuth, as Cycles' version chooses them.
  float share, phi;
  if (cycles4_) {
    const Vec2 d = sample_concentric_disk(u);
    share = glm::dot(d, d);
    phi = std::atan2(d.y, d.x);
  } else {
    share = 1.0f - u.x;
    phi = kTwoPi * u.y;
  }
  const float one_minus_cos = share * one_minus_cos_cone_;
  const float sin_theta = safe_sqrt(one_minus_cos * (2.0f - one_minus_cos));
  const Vec3 local(sin_theta * std::cos(phi), sin_theta * std::sin(phi), 1.0f - one_minus_cos);
  BsdfSample s;
  s.wi = glossy_ ? Frame(Vec3(-wo.x, -wo.y, wo.z)).to_world(local) : local;
  s.diffuse = !glossy_;
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f)) return {};
  // Blender 3.x: Cycles' weight, the fade at theta_s u.x (toon_bsdf.h); 4.x: eval / pdf.
  s.weight = cycles4_ ? eval(wo, s.wi) / s.pdf : color_ * intensity(cone_angle(size_, smooth_) * u.x);
  return s;
}

}  // namespace torrance
