#include "torrance/bsdfs/beckmann.h"

#include <algorithm>
#include <cmath>

namespace torrance::beckmann {

namespace {

constexpr double kSqrtPi = 1.7724538509055160273;
constexpr double kSlopeBound = 7.0;  // exp(-49): no slope of the unit Beckmann lies beyond it

// The root of an increasing f in [lo, hi] (f(lo) <= 0 <= f(hi)): Newton's steps from x, kept
// inside the bracket, which each evaluation narrows (a bisection where a step would leave it).
template <class F, class Df>
double increasing_root(const F& f, const Df& df, double x, double lo, double hi) {
  for (int i = 0; i < 60; ++i) {
    const double fx = f(x);
    (fx > 0.0 ? hi : lo) = x;
    const double slope = df(x);
    double next = slope > 0.0 ? x - fx / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 1e-10 * (1.0 + std::abs(x))) return next;
    x = next;
  }
  return x;
}

// A slope of the unit Beckmann distribution along a view of cotangent cot, in proportion to
// exp(-x^2) (cot - x) on x < cot (the projected area its facet shows the view). Its CDF is
// C(x) = cot sqrt(pi) / 2 erfc(-x) + exp(-x^2) / 2.
double sample_slope_along_view(double cot, double u) {
  const double hi = std::min(cot, kSlopeBound);
  const auto cdf = [cot](double x) { return 0.5 * (cot * kSqrtPi * std::erfc(-x) + std::exp(-x * x)); };
  const double target = u * cdf(hi);
  return increasing_root([&](double x) { return cdf(x) - target; },
                         [cot](double x) { return std::exp(-x * x) * (cot - x); }, std::min(0.0, hi), -kSlopeBound,
                         hi);
}

// A slope across the view: density exp(-y^2) / sqrt(pi), i.e. y = erf^-1(2u - 1).
double sample_slope_across_view(double u) {
  const double target = 2.0 * u - 1.0;
  return increasing_root([target](double y) { return std::erf(y) - target; },
                         [](double y) { return 2.0 / kSqrtPi * std::exp(-y * y); }, 0.0, -kSlopeBound, kSlopeBound);
}

// Cycles' rational Lambda of a^-2 = (alpha tan theta)^2.
float rational_lambda(float alpha2_tan2) {
  if (!(alpha2_tan2 >= 0.39f)) return 0.0f;  // a >= 1.6 (also a normal view or alpha 0)
  const float a = 1.0f / std::sqrt(alpha2_tan2);
  return ((0.396f * a - 1.259f) * a + 1.0f) / ((2.181f * a + 3.535f) * a);
}

// Smith's exact Lambda of a = 1 / (alpha tan theta).
float exact_lambda(double a) {
  if (!(a > 0.0)) return 1e30f;  // grazing: nothing is visible
  if (!std::isfinite(a)) return 0.0f;
  return float(0.5 * (std::exp(-a * a) / (a * kSqrtPi) - std::erfc(a)));
}

// (alpha_x w.x)^2 + (alpha_y w.y)^2 over w.z^2.
float alpha2_tan2(const Vec3& w, float ax, float ay) {
  return (sqr(ax * w.x) + sqr(ay * w.y)) / sqr(w.z);
}

}  // namespace

float D_aniso(const Vec3& h, float ax, float ay) {
  const float c2 = h.z * h.z;
  if (!(h.z > 0.0f) || !(ax * ay > 0.0f)) return 0.0f;
  const float tan2 = (sqr(h.x / ax) + sqr(h.y / ay)) / c2;
  return std::exp(-tan2) / (kPi * ax * ay * c2 * c2);
}

float D(const Vec3& h, float alpha) { return D_aniso(h, alpha, alpha); }

float lambda(float cos_theta, float alpha) {
  const float c2 = cos_theta * cos_theta;
  return rational_lambda(alpha * alpha * std::max(1.0f / c2 - 1.0f, 0.0f));
}

float lambda_aniso(const Vec3& w, float ax, float ay) { return rational_lambda(alpha2_tan2(w, ax, ay)); }

float lambda_exact(float cos_theta, float alpha) {
  const double c = std::abs(double(cos_theta)), s = std::sqrt(std::max(0.0, 1.0 - c * c));
  return exact_lambda(c / (double(alpha) * s));
}

float lambda_exact_aniso(const Vec3& w, float ax, float ay) {
  const double tx = double(ax) * w.x, ty = double(ay) * w.y;
  const double t = std::sqrt(tx * tx + ty * ty);
  return exact_lambda(std::abs(double(w.z)) / t);
}

Vec3 sample_visible_normal_aniso(const Vec3& wo, float ax, float ay, const Vec2& u) {
  // The view stretched to alpha 1, its azimuth and the cotangent of its polar angle.
  glm::dvec3 v(double(ax) * wo.x, double(ay) * wo.y, double(wo.z));
  v /= glm::length(v);
  const double sin_v = std::sqrt(v.x * v.x + v.y * v.y);
  double cos_phi = 1.0, sin_phi = 0.0, cot = 1e6;
  if (sin_v > 1e-12) {
    cos_phi = v.x / sin_v;
    sin_phi = v.y / sin_v;
    cot = std::min(v.z / sin_v, 1e6);
  }
  const double along = sample_slope_along_view(cot, double(u.x));
  const double across = sample_slope_across_view(double(u.y));
  // Turned to the view's azimuth, unstretched: the microfacet normal (-slope_x, -slope_y, 1).
  const double sx = (cos_phi * along - sin_phi * across) * ax;
  const double sy = (sin_phi * along + cos_phi * across) * ay;
  return Vec3(glm::normalize(glm::dvec3(-sx, -sy, 1.0)));
}

Vec3 sample_visible_normal(const Vec3& wo, float alpha, const Vec2& u) {
  return sample_visible_normal_aniso(wo, alpha, alpha, u);
}

float visible_normal_pdf_aniso(const Vec3& wo, const Vec3& h, float ax, float ay) {
  const float o_h = glm::dot(wo, h);
  if (!(wo.z > 0.0f) || !(o_h > 0.0f)) return 0.0f;
  return D_aniso(h, ax, ay) * o_h / (wo.z * (1.0f + lambda_exact_aniso(wo, ax, ay)));
}

float visible_normal_pdf(const Vec3& wo, const Vec3& h, float alpha) {
  return visible_normal_pdf_aniso(wo, h, alpha, alpha);
}

}  // namespace torrance::beckmann
