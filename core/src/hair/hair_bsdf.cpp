// The Hair BSDF node's closure: eval, pdf and sample side by side (see the header for the model).
#include "torrance/hair/hair_bsdf.h"

#include "torrance/hair/strand_direction.h"

#include <algorithm>
#include <cmath>

namespace torrance {
namespace {

constexpr float kHalfPi = 0.5f * kPi;
// Cycles leaves out directions within this angle (radians) of the strand's own direction.
constexpr float kPoleMargin = 0.001f;

float roughness(float r) { return std::isfinite(r) ? std::clamp(r, 0.001f, 1.0f) : 0.001f; }

// The longitudinal angle of a unit direction whose cosine to the strand is `along`.
float longitude(float along) { return std::asin(std::clamp(along, -1.0f, 1.0f)); }

// The unit part of v across the strand t (false where v lies along it).
bool across(const Vec3& v, const Vec3& t, float along, Vec3& out) {
  const Vec3 d = v - t * along;
  const float len = glm::length(d);
  if (!(len > 1e-7f)) return false;
  out = d / len;
  return true;
}

}  // namespace

struct HairBsdf::View {
  bool valid = false;
  Vec3 locy{0.0f}, locx{0.0f};
  float theta_r = 0.0f;
  float a = 0.0f, b = 0.0f;  // the longitudinal lobe's bounds in atan space
};

HairBsdf::HairBsdf(const Vec3& color, bool transmission, float roughness_u, float roughness_v, float offset,
                   const Vec3& tangent)
    : color_(glm::max(color, Vec3(0.0f))),
      transmission_(transmission),
      r1_(roughness(roughness_u)),
      r2_(roughness(roughness_v)),
      offset_(std::isfinite(offset) ? -offset : 0.0f),
      world_tangent_(tangent) {
  const float len = glm::length(tangent);  // as given, until orient() turns it
  if (len > 0.0f && std::isfinite(len)) tangent_ = tangent / len;
}

void HairBsdf::orient(const Frame& frame) { tangent_ = strand_in_frame(frame, world_tangent_); }

HairBsdf::View HairBsdf::at(const Vec3& wo) const {
  View v;
  const float along = glm::dot(tangent_, wo);
  if (!across(wo, tangent_, along, v.locy)) return v;
  v.locx = glm::cross(v.locy, tangent_);
  v.theta_r = longitude(along);
  v.a = std::atan(((kHalfPi + v.theta_r) * 0.5f - offset_) / r1_);
  v.b = std::atan(((-kHalfPi + v.theta_r) * 0.5f - offset_) / r1_);
  v.valid = v.a > v.b;
  return v;
}

float HairBsdf::density(const View& v, const Vec3& wi, bool cut) const {
  if (!v.valid) return 0.0f;
  const float along = glm::dot(tangent_, wi);
  Vec3 wi_across;
  if (!across(wi, tangent_, along, wi_across)) return 0.0f;
  const float theta_i = longitude(along);
  if (kHalfPi - std::abs(theta_i) < kPoleMargin) return 0.0f;
  const float cos_phi = std::clamp(glm::dot(wi_across, v.locy), -1.0f, 1.0f);
  float phi_pdf;
  if (!transmission_) {
    if (cut && (wi.z < 0.0f || cos_phi < 0.0f)) return 0.0f;
    const float phi = std::min(std::acos(cos_phi) / r2_, kPi);
    phi_pdf = std::max(std::cos(0.5f * phi), 0.0f) * 0.25f / r2_;
  } else {
    if (cut && wi.z >= 0.0f) return 0.0f;
    if (!cut && cos_phi > 0.0f) return 0.0f;  // drawn within 90 degrees of -wo, evaluated beyond
    const float p = kPi - std::acos(cos_phi);
    phi_pdf = r2_ / (2.0f * std::atan(kHalfPi / r2_) * (p * p + r2_ * r2_));
  }
  const float t = 0.5f * (theta_i + v.theta_r) - offset_;
  const float theta_pdf = r1_ / (2.0f * (t * t + r1_ * r1_) * (v.a - v.b) * std::cos(theta_i));
  const float d = phi_pdf * theta_pdf;
  return std::isfinite(d) && d > 0.0f ? d : 0.0f;
}

LobeEval HairBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  LobeEval f;
  f.glossy = color_ * density(at(wo), wi, true);
  return f;
}

float HairBsdf::pdf(const Vec3& wo, const Vec3& wi) const { return density(at(wo), wi, true); }

float HairBsdf::sampling_density(const Vec3& wo, const Vec3& wi) const { return density(at(wo), wi, false); }

BsdfSample HairBsdf::sample(const Vec3& wo, float /*u_lobe*/, const Vec2& u) const {
  const View v = at(wo);
  if (!v.valid) return {};
  // The longitude: Cauchy about the tilted mirror direction.
  const float t = r1_ * std::tan(u.x * (v.a - v.b) + v.b);
  const float theta_i = 2.0f * (t + offset_) - v.theta_r;
  if (kHalfPi - std::abs(theta_i) < kPoleMargin) return {};
  const float cos_theta = std::cos(theta_i), sin_theta = std::sin(theta_i);
  const float theta_pdf = r1_ / (2.0f * (t * t + r1_ * r1_) * (v.a - v.b) * cos_theta);
  // The azimuth from wo across the strand, and Cycles' pdf of it.
  float phi, phi_pdf;
  if (!transmission_) {
    phi = 2.0f * std::asin(std::clamp(1.0f - 2.0f * u.y, -1.0f, 1.0f)) * r2_;
    phi_pdf = std::cos(0.5f * phi) * 0.25f / r2_;  // Cycles': phi where its density has phi / r2
  } else {
    const float c = 2.0f * std::atan(kHalfPi / r2_);
    const float p = r2_ * std::tan(c * (u.y - 0.5f));
    phi = p + kPi;
    phi_pdf = r2_ / (c * (p * p + r2_ * r2_));
  }
  BsdfSample s;
  s.wi = (std::cos(phi) * cos_theta) * v.locy - (std::sin(phi) * cos_theta) * v.locx + sin_theta * tangent_;
  // (Left out near the strand as density() finds it: float's asin there is coarser than theta_i.)
  if (kHalfPi - std::abs(longitude(glm::dot(tangent_, s.wi))) < kPoleMargin) return {};
  s.pdf = std::abs(phi_pdf * theta_pdf);
  if (!(s.pdf > 0.0f) || !std::isfinite(s.pdf) || !is_finite(s.wi)) return {};
  s.weight = color_;  // Cycles' eval of its sample is its pdf
  return s;
}

}  // namespace torrance
