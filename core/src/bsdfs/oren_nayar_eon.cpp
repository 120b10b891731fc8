#include "torrance/bsdfs/oren_nayar_eon.h"

#include "torrance/bsdfs/cosine_sampled.h"
#include "torrance/util/sampling.h"

namespace torrance {

namespace {

constexpr float kGrazingG = 0.5f * kPi - 2.0f / 3.0f;             // G(0)
constexpr float kMeanG = (2.0f * kPi - 5.6f) / 3.0f;              // 2 int G(mu) mu dmu
constexpr float kLambertBelow = 1e-5f;                            // Cycles' roughness threshold

// Fujii's G(mu): the single-scatter albedo is pi A + B G(mu).
float fujii_g(float cos_theta) {
  if (cos_theta < 1e-6f) return kGrazingG - cos_theta;  // its expansion at grazing (tan blows up)
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float theta = std::acos(std::min(cos_theta, 1.0f));
  return sin_theta * (theta - 2.0f / 3.0f - sin_theta * cos_theta) +
         2.0f / 3.0f * (sin_theta / cos_theta) * (1.0f - sin_theta * sin_theta * sin_theta);
}

}  // namespace

EnergyPreservingOrenNayar::EnergyPreservingOrenNayar(const Vec3& color, float roughness) {
  const float sigma = std::isfinite(roughness) ? clamp01(roughness) : 0.0f;
  if (sigma < kLambertBelow) return;  // Lambert
  a_ = 1.0f / (kPi + kGrazingG * sigma);
  b_ = sigma * a_;
  rho_ = glm::clamp(color, Vec3(0.0f), Vec3(1.0f));
  loss_avg_ = b_ * (kGrazingG - kMeanG);
  const Vec3 rho_ms = rho_ * (1.0f - loss_avg_) / (Vec3(1.0f) - rho_ * loss_avg_);
  multi_ = rho_ms / (kPi * loss_avg_);
}

float EnergyPreservingOrenNayar::loss(float cos_theta) const {
  return std::max(0.0f, b_ * (kGrazingG - fujii_g(clamp01(cos_theta))));
}

float EnergyPreservingOrenNayar::single_scatter_albedo(float cos_o) const { return 1.0f - loss(cos_o); }

Vec3 EnergyPreservingOrenNayar::albedo(float cos_o) const {
  const float loss_o = loss(cos_o);
  return Vec3(1.0f - loss_o) + rho_ * ((1.0f - loss_avg_) * loss_o) / (Vec3(1.0f) - rho_ * loss_avg_);
}

Vec3 EnergyPreservingOrenNayar::reflectance_cos(float cos_i, float cos_o, float cos_io) const {
  if (!(cos_i > 0.0f)) return Vec3(0.0f);
  if (lambertian()) return Vec3(cos_i * kInvPi);
  cos_o = std::max(cos_o, 0.0f);
  float t = cos_io - cos_i * cos_o;
  if (t > 0.0f) t /= std::max(cos_i, cos_o);  // Fujii divides positive t only
  const float single = a_ + b_ * t;
  return cos_i * (Vec3(single) + multi_ * (loss(cos_i) * loss(cos_o)));
}

float EnergyPreservingOrenNayar::pdf(const Vec3& /*wo*/, const Vec3& wi) const {
  return cosine_hemisphere_pdf(wi.z);
}

BsdfSample EnergyPreservingOrenNayar::sample(const Vec3& wo, const Vec2& u) const {
  return sample_cosine_weighted(*this, wo, u);
}

}  // namespace torrance
