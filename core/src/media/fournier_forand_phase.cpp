#include "torrance/media/fournier_forand_phase.h"

#include <algorithm>
#include <cmath>

namespace torrance {

namespace {

constexpr double kTaylor = 1e-3;  // |1 - delta| below it: the first-order expansions about delta = 1

double delta_of(double n, double x) { return 4.0 * x / (3.0 * (n - 1.0) * (n - 1.0)); }

}  // namespace

FournierForandPhase::FournierForandPhase(float ior, float backscatter) {
  const double b = std::min(std::isfinite(backscatter) ? std::abs(double(backscatter)) : 0.0, 0.5 - 1e-3);
  n_ = std::max(std::isfinite(ior) ? double(ior) : 1.0, 1.0 + 1e-3);
  const double d90 = delta_of(n_, 0.5), d180 = delta_of(n_, 1.0);
  v_ = -std::log(2.0 * b * (d90 - 1.0) + 1.0) / std::log(d90);
  c3_ = (std::pow(d180, -v_) - 1.0) / (d180 - 1.0);
}

double FournierForandPhase::value(double x) const {
  if (!(x > 0.0)) return 0.0;  // the forward peak itself (integrable, unbounded)
  const double c = 1.0 - 2.0 * x, delta = delta_of(n_, x), v = v_;
  const double d_v = std::pow(delta, v), m = 1.0 - delta, m_v = 1.0 - d_v;
  double p;
  if (std::abs(m) < kTaylor)
    p = v * ((v - 1.0) - (v + 1.0) / x) / (8.0 * M_PI) +
        v * (v + 1.0) * m * (2.0 * (v - 1.0) - (2.0 * v + 1.0) / x) / (24.0 * M_PI);
  else
    p = (v * m - m_v + (delta * m_v - v * m) / x) / (4.0 * M_PI * m * m * d_v);
  p += c3_ / (16.0 * M_PI) * (3.0 * c * c - 1.0);
  return std::max(p, 0.0);
}

double FournierForandPhase::cdf(double x) const {
  if (!(x > 0.0)) return 0.0;
  const double c = 1.0 - 2.0 * x, delta = delta_of(n_, x), v = v_;
  const double d_v = std::pow(delta, v), m = 1.0 - delta;
  double f;
  if (std::abs(m) < kTaylor) f = 1.0 + v * (1.0 - x) * (1.0 - 0.5 * (v + 1.0) * m);
  else f = (1.0 - d_v * delta - (1.0 - d_v) * x) / (m * d_v);
  return f + c3_ / 8.0 * c * (1.0 - c * c);
}

float FournierForandPhase::eval(const Vec3& wo, const Vec3& wi) const {
  const Vec3 h = wi + wo;  // |wi - (-wo)|^2 = 4 sin^2(theta / 2)
  return float(value(std::min(0.25 * double(glm::dot(h, h)), 1.0)));
}

PhaseSample FournierForandPhase::sample(const Vec3& wo, const Vec2& u) const {
  // cdf(x) = u on x in (0, 1]: cdf rises from 0 to 1, its slope 4 pi p(x) (dx = -dcos / 2).
  // Newton steps kept inside the bracket; where one leaves it, the bracket's geometric middle
  // (its arithmetic one while the lower end is 0), for the peak spans decades of x.
  double lo = 0.0, hi = 1.0, x = 0.17860619515673;  // a start at 50 degrees
  const double target = u.x;
  for (int n = 0; n < 100; ++n) {
    const double f = cdf(x) - target;
    if (f > 0.0) hi = x;
    else lo = x;
    const double slope = 4.0 * M_PI * value(x);
    double next = slope > 0.0 ? x - f / slope : -1.0;
    if (!(next > lo && next < hi)) next = lo > 0.0 ? std::sqrt(lo * hi) : 1e-3 * hi;
    const bool done = std::abs(next - x) <= 1e-10 * x;
    x = next;
    if (done) break;
  }
  const double cos_theta = 1.0 - 2.0 * x, sin_theta = 2.0 * std::sqrt(std::max(x * (1.0 - x), 0.0));
  const float phi = kTwoPi * u.y;
  const Frame around(-wo);
  PhaseSample s;
  s.wi = glm::normalize(around.to_world(
      Vec3(float(sin_theta) * std::cos(phi), float(sin_theta) * std::sin(phi), float(cos_theta))));
  s.pdf = eval(wo, s.wi);
  return s;
}

}  // namespace torrance
