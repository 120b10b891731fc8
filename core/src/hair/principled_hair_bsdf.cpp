// The Principled Hair BSDF: eval, pdf and sample side by side (see the header for the model).
#include "torrance/hair/principled_hair_bsdf.h"

#include "torrance/hair/strand_direction.h"

#include "torrance/bsdfs/principled.h"  // fresnel_dielectric

#include <algorithm>
#include <cmath>

namespace torrance {
namespace {



float cos_from_sin(float s) { return std::sqrt(std::max(1.0f - s * s, 0.0f)); }
float safe_asin(float s) { return std::asin(std::clamp(s, -1.0f, 1.0f)); }


// The azimuthal change of direction of lobe p (Chiang's Phi).
float delta_phi(int p, float gamma_o, float gamma_t) { return 2.0f * p * gamma_t - 2.0f * gamma_o + p * kPi; }

float wrap_angle(float a) { return (a + kPi) - 2.0f * kPi * std::floor((a + kPi) / (2.0f * kPi)) - kPi; }

float logistic(float x, float s) {
  const float e = std::exp(-std::abs(x) / s);
  return e / (s * sqr(1.0f + e));
}

float logistic_cdf(float x, float s) {
  const float arg = -x / s;
  return arg > 88.0f ? 0.0f : 1.0f / (1.0f + std::exp(arg));
}

// The logistic distribution restricted to [-pi, pi] and renormalised.
float trimmed_logistic(float x, float s) {
  const float mass = 1.0f - 2.0f * logistic_cdf(-kPi, s);
  return mass > 0.0f ? logistic(x, s) / mass : 0.0f;
}

float sample_trimmed_logistic(float u, float s) {
  const float below = logistic_cdf(-kPi, s);
  const float x = -s * std::log(1.0f / (u * (1.0f - 2.0f * below) + below) - 1.0f);
  return std::clamp(x, -kPi, kPi);
}

// The modified Bessel function I0 by its series (as Cycles: up to 10 terms).
float bessel_i0(float x) {
  x = x * x;
  float value = 1.0f + 0.25f * x;
  float x_pow = x * x;
  double factorial_sq = 1.0;
  float four_pow = 16.0f;
  for (int i = 2; i < 10; ++i) {
    factorial_sq *= double(i) * double(i);
    const float next = value + float(x_pow / (four_pow * factorial_sq));
    if (next == value) return value;
    value = next;
    x_pow *= x;
    four_pow *= 4.0f;
  }
  return value;
}

float log_bessel_i0(float x) {
  constexpr float kLog2Pi = 1.83787706641f;
  if (x > 12.0f) return x + 0.5f * (1.0f / (8.0f * x) - kLog2Pi - std::log(x));
  return std::log(bessel_i0(x));
}

// M_p without Cycles' approximations of I0 (its series cut at 10 terms, its asymptote's
// 1 / (16 x) for 1 / (8 x)): the density its sampling draws theta by, for the pdf.
double log_bessel_i0_exact(double x) {
  if (x > 30.0) return x - 0.5 * std::log(2.0 * M_PI * x) + std::log1p(1.0 / (8.0 * x) + 9.0 / (128.0 * x * x));
  const double q = 0.25 * x * x;
  double term = 1.0, sum = 1.0;
  for (int i = 1; i < 200 && term > 1e-17 * sum; ++i) {
    term *= q / (double(i) * double(i));
    sum += term;
  }
  return std::log(sum);
}

float longitudinal_exact(float sin_i, float cos_i, float sin_o, float cos_o, float v) {
  const double a = 1.0 / double(v);
  const double log_m = log_bessel_i0_exact(double(cos_i) * cos_o * a) - double(sin_i) * sin_o * a - a;
  return float(std::exp(log_m) * a / -std::expm1(-2.0 * a));
}

// The density in theta (not yet per solid angle) with which sample() draws theta_i for a lobe
// whose M_p-distributed theta' is moved by `shift` (theta_i = theta' + shift, folded back over
// a pole where it passes one, as Cycles' |cos| does): M_p(theta') cos(theta') summed over every
// theta' in [-pi/2, pi/2] that lands on theta_i.
float tilted_theta_density(float theta_i, float shift, float sin_o, float cos_o, float v) {
  const float half_pi = 0.5f * kPi;
  float density = 0.0f;
  for (float x : {theta_i, kPi - theta_i, -kPi - theta_i}) {
    const float theta = x - shift;
    if (theta < -half_pi || theta > half_pi) continue;
    const float c = std::cos(theta);
    density += longitudinal_exact(std::sin(theta), c, sin_o, cos_o, v) * c;
  }
  return density;
}

// sin and |cos| of theta_i tilted by the scales for R (2 alpha), TT (-alpha) and TRT (-4 alpha),
// as pairs: angles[2p], angles[2p + 1].
void tilted_angles(float sin_i, float cos_i, float alpha, float angles[6]) {
  const float sin_1 = std::sin(alpha), cos_1 = cos_from_sin(sin_1);
  const float sin_2 = 2.0f * sin_1 * cos_1, cos_2 = sqr(cos_1) - sqr(sin_1);
  const float sin_4 = 2.0f * sin_2 * cos_2, cos_4 = sqr(cos_2) - sqr(sin_2);
  angles[0] = sin_i * cos_2 + cos_i * sin_2;
  angles[1] = std::abs(cos_i * cos_2 - sin_i * sin_2);
  angles[2] = sin_i * cos_1 - cos_i * sin_1;
  angles[3] = std::abs(cos_i * cos_1 + sin_i * sin_1);
  angles[4] = sin_i * cos_4 - cos_i * sin_4;
  angles[5] = std::abs(cos_i * cos_4 + sin_i * sin_4);
}

Vec3 safe_ratio(const Vec3& a, const Vec3& b) {
  Vec3 r;
  for (int c = 0; c < 3; ++c) r[c] = b[c] != 0.0f ? a[c] / b[c] : 0.0f;
  return r;
}

// Roughness -> the logistic's scale (Chiang's fit), and -> the longitudinal variance.
float azimuthal_scale(float s) {
  constexpr float kSqrtPiOver8 = 0.626657069f;
  return (0.265f * s + 1.194f * sqr(s) + 5.372f * std::pow(s, 22.0f)) * kSqrtPiOver8;
}
float longitudinal_variance(float v) { return sqr(0.726f * v + 0.812f * sqr(v) + 3.7f * std::pow(v, 20.0f)); }

}  // namespace

namespace chiang {

float longitudinal(float sin_i, float cos_i, float sin_o, float cos_o, float v) {
  const float inv_v = 1.0f / v;
  const float cos_arg = cos_i * cos_o * inv_v, sin_arg = sin_i * sin_o * inv_v;
  if (v <= 0.1f) return std::exp(log_bessel_i0(cos_arg) - sin_arg - inv_v + 0.6931f + std::log(0.5f * inv_v));
  return std::exp(-sin_arg) * bessel_i0(cos_arg) / (std::sinh(inv_v) * 2.0f * v);
}

float sample_longitudinal_sin(const Vec2& u, float v, float sin_o, float cos_o) {
  const float u1 = std::max(u.x, 1e-5f);
  const float fac = 1.0f + v * std::log(u1 + (1.0f - u1) * std::exp(-2.0f / v));
  return std::clamp(-fac * sin_o + cos_from_sin(fac) * std::cos(2.0f * kPi * u.y) * cos_o, -1.0f, 1.0f);
}

}  // namespace chiang

struct PrincipledHairBsdf::Strand {
  Vec3 x, y, z;  // the strand's frame for this wo
  float sin_theta_o = 0.0f, cos_theta_o = 1.0f, phi_o = 0.0f;
  float gamma_o = 0.0f, gamma_t = 0.0f;
  Vec3 ap[4];        // A_p
  float share[4]{};  // |A_p| / sum_q |A_q|
};

PrincipledHairBsdf::PrincipledHairBsdf(const PrincipledHairParams& p, const Vec3& tangent)
    : sigma_(glm::max(p.sigma, Vec3(0.0f))), alpha_(p.offset), eta_(p.ior), tangent_(tangent), world_tangent_(tangent) {
  const float v = std::clamp(p.roughness, 0.001f, 1.0f);
  const float s = std::clamp(p.radial_roughness, 0.001f, 1.0f);
  const float v_r = std::clamp((1.0f - clamp01(p.coat)) * v, 0.001f, 1.0f);
  v_ = longitudinal_variance(v);
  s_ = azimuthal_scale(s);
  v_r_ = longitudinal_variance(v_r);
  if (!(eta_ > 0.0f) || !std::isfinite(eta_)) eta_ = 1.55f;
  const float len = glm::length(tangent_);
  tangent_ = len > 0.0f && std::isfinite(len) ? tangent_ / len : Vec3(1.0f, 0.0f, 0.0f);
}

void PrincipledHairBsdf::orient(const Frame& frame) { tangent_ = strand_in_frame(frame, world_tangent_); }

PrincipledHairBsdf::Strand PrincipledHairBsdf::at(const Vec3& wo) const {
  Strand s;
  s.x = tangent_;
  Vec3 y = glm::cross(s.x, wo);
  float len = glm::length(y);
  if (!(len > 1e-7f)) {  // looking along the strand: any direction across it
    y = glm::cross(s.x, std::abs(s.x.z) < 0.9f ? Vec3(0, 0, 1) : Vec3(1, 0, 0));
    len = glm::length(y);
  }
  s.y = y / len;
  s.z = glm::normalize(glm::cross(s.x, s.y));
  const float h = std::clamp(-s.y.z, -1.0f, 1.0f);  // -N.Y, N the shading frame's z
  s.sin_theta_o = std::clamp(glm::dot(wo, s.x), -1.0f, 1.0f);
  s.cos_theta_o = cos_from_sin(s.sin_theta_o);
  s.phi_o = std::atan2(glm::dot(wo, s.z), glm::dot(wo, s.y));
  const float sin_theta_t = s.sin_theta_o / eta_;
  const float cos_theta_t = cos_from_sin(sin_theta_t);
  const float cos_gamma_o = cos_from_sin(h);
  s.gamma_o = safe_asin(h);
  const float sin_gamma_t = h * s.cos_theta_o / std::sqrt(std::max(sqr(eta_) - sqr(s.sin_theta_o), 1e-12f));
  const float cos_gamma_t = cos_from_sin(sin_gamma_t);
  s.gamma_t = safe_asin(sin_gamma_t);
  const Vec3 t = cos_theta_t > 0.0f ? glm::exp(-sigma_ * (2.0f * cos_gamma_t / cos_theta_t)) : Vec3(0.0f);
  const float f = fresnel_dielectric(s.cos_theta_o * cos_gamma_o, eta_);
  s.ap[0] = Vec3(f);
  s.ap[1] = sqr(1.0f - f) * t;
  s.ap[2] = s.ap[1] * t * f;
  s.ap[3] = s.ap[2] * safe_ratio(t * f, Vec3(1.0f) - t * f);
  float total = 0.0f;
  for (int p = 0; p < 4; ++p) total += (s.share[p] = std::max(luminance(s.ap[p]), 0.0f));
  for (int p = 0; p < 4; ++p) s.share[p] = total > 0.0f ? s.share[p] / total : 0.0f;
  return s;
}

Vec3 PrincipledHairBsdf::eval_at(const Strand& s, const Vec3& wi, float& pdf) const {
  const float sin_theta_i = std::clamp(glm::dot(wi, s.x), -1.0f, 1.0f);
  const float cos_theta_i = cos_from_sin(sin_theta_i);
  const float phi = std::atan2(glm::dot(wi, s.z), glm::dot(wi, s.y)) - s.phi_o;
  float angles[6];
  tilted_angles(sin_theta_i, cos_theta_i, alpha_, angles);
  Vec3 f(0.0f);
  pdf = 0.0f;
  // sample() draws a lobe's theta' by M_p and tilts it by the scales: its density per solid
  // angle at theta_i is M_p(theta') cos(theta') / cos(theta_i) (where Cycles' pdf leaves out
  // that ratio, which its samples then are not drawn by).
  const float inv_cos_i = 1.0f / std::max(cos_theta_i, 1e-6f);
  const float theta_i = std::asin(sin_theta_i);
  const float shifts[3] = {-2.0f * alpha_, alpha_, 4.0f * alpha_};  // where sample() moves theta'
  for (int p = 0; p < 3; ++p) {
    const float v = p == 0 ? v_r_ : p == 1 ? 0.25f * v_ : 4.0f * v_;
    const float m = chiang::longitudinal(angles[2 * p], angles[2 * p + 1], s.sin_theta_o, s.cos_theta_o, v);
    const float n = trimmed_logistic(wrap_angle(phi - delta_phi(p, s.gamma_o, s.gamma_t)), s_);
    f += s.ap[p] * (m * n);
    if (s.share[p] > 0.0f)
      pdf += s.share[p] * tilted_theta_density(theta_i, shifts[p], s.sin_theta_o, s.cos_theta_o, v) * n * inv_cos_i;
  }
  const float m = chiang::longitudinal(sin_theta_i, cos_theta_i, s.sin_theta_o, s.cos_theta_o, 4.0f * v_);
  constexpr float kInv2Pi = 0.159154943f;
  f += s.ap[3] * (m * kInv2Pi);
  if (s.share[3] > 0.0f)
    pdf += s.share[3] * longitudinal_exact(sin_theta_i, cos_theta_i, s.sin_theta_o, s.cos_theta_o, 4.0f * v_) *
           kInv2Pi;
  if (!is_finite(f) || !std::isfinite(pdf)) {
    pdf = 0.0f;
    return Vec3(0.0f);
  }
  return f;
}

LobeEval PrincipledHairBsdf::eval_lobes(const Vec3& wo, const Vec3& wi) const {
  float pdf;
  LobeEval e;
  e.glossy = eval_at(at(wo), wi, pdf);
  return e;
}

float PrincipledHairBsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  float pdf;
  eval_at(at(wo), wi, pdf);
  return pdf;
}

BsdfSample PrincipledHairBsdf::sample(const Vec3& wo, float u_lobe, const Vec2& u) const {
  const Strand s = at(wo);
  // The lobe by its share; what is left of u_lobe samples the azimuth.
  int p = 0;
  float lower = 0.0f;
  while (p < 3 && u_lobe >= lower + s.share[p]) lower += s.share[p++];
  if (!(s.share[p] > 0.0f)) return {};
  const float u_phi = std::clamp((u_lobe - lower) / s.share[p], 0.0f, 0.99999994f);
  // theta: the lobe's M_p about the mirror direction (exactly), then untilted.
  const float v = p == 0 ? v_r_ : p == 1 ? 0.25f * v_ : 4.0f * v_;
  float sin_theta_i = chiang::sample_longitudinal_sin(u, v, s.sin_theta_o, s.cos_theta_o);
  float cos_theta_i = cos_from_sin(sin_theta_i);
  if (p < 3) {
    float angles[6];
    tilted_angles(sin_theta_i, cos_theta_i, -alpha_, angles);
    sin_theta_i = angles[2 * p];
    cos_theta_i = angles[2 * p + 1];
  }
  const float phi = p < 3 ? delta_phi(p, s.gamma_o, s.gamma_t) + sample_trimmed_logistic(u_phi, s_)
                          : 2.0f * kPi * u_phi;
  const float phi_i = s.phi_o + phi;
  BsdfSample out;
  out.wi = s.x * sin_theta_i + s.y * (cos_theta_i * std::cos(phi_i)) + s.z * (cos_theta_i * std::sin(phi_i));
  const float len = glm::length(out.wi);
  if (!(len > 0.0f) || !std::isfinite(len)) return {};
  out.wi /= len;
  float pdf;
  const Vec3 f = eval_at(s, out.wi, pdf);
  if (!(pdf > 0.0f)) return {};
  out.pdf = pdf;
  out.weight = f / pdf;
  return out;
}

float PrincipledHairBsdf::sampling_albedo() const {
  const float x = v_;  // as Cycles: the longitudinal variance in the polynomial of the roughness
  const float scale = (((((0.245f * x) + 5.574f) * x - 10.73f) * x + 2.532f) * x - 0.215f) * x + 5.969f;
  return luminance(glm::exp(-glm::sqrt(sigma_) * scale));
}

Vec3 HairRandomness::sigma_at(float r, float& roughness, float& radial) const {
  const float shift = 2.0f * (r - 0.5f);
  const float scale = 1.0f + shift * random_roughness;
  roughness *= scale;
  radial *= scale;
  switch (coloring) {
    case Coloring::Absorption: return sigma;
    case Coloring::Melanin: {
      const float m = melanin * (1.0f + shift * clamp01(random_color));
      const float amount = -std::log(std::max(1.0f - m, 1e-4f));
      return PrincipledHairBsdf::sigma_from_concentration(amount * (1.0f - melanin_redness), amount * melanin_redness) +
             PrincipledHairBsdf::sigma_from_reflectance(color, radial);
    }
    case Coloring::DirectColor: return PrincipledHairBsdf::sigma_from_reflectance(color, radial);
  }
  return sigma;
}

Vec3 PrincipledHairBsdf::sigma_from_concentration(float eumelanin, float pheomelanin) {
  return eumelanin * Vec3(0.506f, 0.841f, 1.653f) + pheomelanin * Vec3(0.343f, 0.733f, 1.924f);
}

Vec3 PrincipledHairBsdf::sigma_from_reflectance(const Vec3& color, float radial_roughness) {
  const float x = radial_roughness;
  const float scale = (((((0.245f * x) + 5.574f) * x - 10.73f) * x + 2.532f) * x - 0.215f) * x + 5.969f;
  const Vec3 sigma = glm::log(glm::max(color, Vec3(1e-30f))) / scale;
  return sigma * sigma;
}

}  // namespace torrance
