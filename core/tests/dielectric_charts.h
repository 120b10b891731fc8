// Binning of directions around both lobes of a dielectric BSDF (reflection and refraction), for
// chi-square tests of its sampling and quadrature of its energy (test_rough_dielectric.cpp,
// test_glass.cpp).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/util/sampling.h"

#include "test_helpers.h"  // drawn_pdf

#include <algorithm>
#include <cmath>
#include <vector>

namespace torrance::test {

// Refraction of wo through the macro surface (the centre of the transmission lobe); -wo under TIR.
inline Vec3 refracted_centre(const Vec3& wo, float ior) {
  const float side = wo.z > 0.0f ? 1.0f : -1.0f, etap = wo.z > 0.0f ? ior : 1.0f / ior;
  const float c = std::abs(wo.z), sin2_t = (1.0f - c * c) / (etap * etap);
  if (sin2_t >= 1.0f) return -wo;
  return glm::normalize(-wo / etap + (c / etap - std::sqrt(1.0f - sin2_t)) * Vec3(0, 0, side));
}

// Two charts cover the sphere: directions on wo's side are binned around the mirror direction,
// directions on the other side around the refracted direction. In each, the angle t from the
// centre maps to s = t / (t + scale) (so a lobe of any width spans many bins) and the azimuth
// is uniform. Bin k of chart c is index c * kBins + k; the last index collects samples without a
// density (delta or rejected).
inline constexpr int kThetaBins = 20, kPhiBins = 24, kBins = kThetaBins * kPhiBins;

struct Charts {
  Frame frame[2];
  float scale[2];
  float side;  // sign of wo.z: chart 0 holds directions with z * side > 0

  Charts(const Vec3& wo, float ior, float alpha) : side(wo.z > 0.0f ? 1.0f : -1.0f) {
    const float etap = wo.z > 0.0f ? ior : 1.0f / ior;
    frame[0] = Frame(Vec3(-wo.x, -wo.y, wo.z));
    frame[1] = Frame(refracted_centre(wo, ior));
    scale[0] = std::max(2.0f * alpha, 2e-3f);
    scale[1] = std::max(2.0f * alpha * std::abs(etap - 1.0f) / etap, 2e-5f);
  }
  int chart_of(const Vec3& w) const { return w.z * side > 0.0f ? 0 : 1; }
  int bin_of(const Vec3& w) const {
    const int c = chart_of(w);
    const Vec3 l = frame[c].to_local(w);
    const float t = std::atan2(std::sqrt(l.x * l.x + l.y * l.y), l.z);
    const float s = t / (t + scale[c]);
    float phi = std::atan2(l.y, l.x);
    if (phi < 0) phi += kTwoPi;
    const int i = std::min(int(s * kThetaBins), kThetaBins - 1);
    const int j = std::min(int(phi / kTwoPi * kPhiBins), kPhiBins - 1);
    return c * kBins + i * kPhiBins + j;
  }
  // Integral of fn over bin (i, j) of chart c, restricted to the chart's side, midpoint rule with
  // sub x sub cells in (s, phi) and the Jacobian of t(s).
  template <typename Fn>
  double integrate(int c, int i, int j, int sub, Fn fn) const {
    double sum = 0.0;
    for (int a = 0; a < sub; ++a)
      for (int b = 0; b < sub; ++b) {
        const double s = (i + (a + 0.5) / sub) / kThetaBins;
        const double phi = (j + (b + 0.5) / sub) / kPhiBins * 2 * M_PI;
        const double t = scale[c] * s / (1.0 - s);
        if (t >= M_PI) continue;
        const double dt_ds = scale[c] / ((1.0 - s) * (1.0 - s));
        const Vec3 l(float(std::sin(t) * std::cos(phi)), float(std::sin(t) * std::sin(phi)), float(std::cos(t)));
        const Vec3 w = frame[c].to_world(l);
        if (chart_of(w) != c) continue;
        sum += double(fn(w)) * std::sin(t) * dt_ds;
      }
    return sum * (1.0 / kThetaBins) * (2 * M_PI / kPhiBins) / (sub * sub);
  }
  // Per-bin integrals of fn, refined to 64 x 64 where 8 x 8 and 16 x 16 disagree.
  template <typename Fn>
  std::vector<double> integrate_all(Fn fn) const {
    std::vector<double> out(2 * kBins, 0.0);
    for (int c = 0; c < 2; ++c)
      for (int i = 0; i < kThetaBins; ++i)
        for (int j = 0; j < kPhiBins; ++j) {
          const double coarse = integrate(c, i, j, 8, fn), fine = integrate(c, i, j, 16, fn);
          out[c * kBins + i * kPhiBins + j] = std::abs(fine - coarse) > 1e-3 * std::abs(fine) + 1e-8
                                                  ? integrate(c, i, j, 64, fn)
                                                  : fine;
        }
    return out;
  }
};

inline double p_value(double x, int dof) {  // chi-square upper tail (Wilson-Hilferty)
  const double k = dof, z = (std::cbrt(x / k) - (1.0 - 2.0 / (9.0 * k))) / std::sqrt(2.0 / (9.0 * k));
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

// Bin counts of n directions sampled from bsdf for wo: the last bin counts samples without a
// density (delta lobes, rejected samples).
template <class Bsdf>
std::vector<double> sampled_bins(const Bsdf& bsdf, const Vec3& wo, const Charts& charts, Rng& rng, int n) {
  std::vector<double> observed(2 * kBins + 1, 0.0);
  for (int i = 0; i < n; ++i) {
    const float u_lobe = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, u_lobe, rng.next_2d());
    if (!s.valid() || s.is_delta) observed.back() += 1;
    else observed[charts.bin_of(s.wi)] += 1;
  }
  return observed;
}

// Expected counts per bin of n samples drawn with density pdf (its quadrature over the charts),
// the last bin expecting what is left, 1 - mass (mass: the quadrature's total).
template <class Pdf>
std::vector<double> expected_bins(const Charts& charts, const Pdf& pdf, int n, double& mass) {
  std::vector<double> expected = charts.integrate_all(pdf);
  mass = 0.0;
  for (double e : expected) mass += e;
  expected.push_back(std::max(0.0, 1.0 - mass));
  for (double& e : expected) e *= n;
  return expected;
}

// Pearson's chi-square of observed bin counts against expected counts; bins expecting fewer than
// 5 are pooled into one, which counts as a bin only if it expects 5 or more itself (otherwise the
// caller bounds pooled_observed by pooled_expected).
struct ChiSquare {
  double chi2 = 0.0;
  int dof = -1;
  double pooled_observed = 0.0, pooled_expected = 0.0;
  bool pooled_counted = false;
  double p() const { return dof > 0 ? p_value(chi2, dof) : 1.0; }
};
inline ChiSquare pooled_chi_square(const std::vector<double>& observed, const std::vector<double>& expected) {
  ChiSquare x;
  for (size_t k = 0; k < expected.size(); ++k) {
    const double e = expected[k];
    if (e < 5.0) {
      x.pooled_observed += observed[k];
      x.pooled_expected += e;
      continue;
    }
    x.chi2 += (observed[k] - e) * (observed[k] - e) / e;
    ++x.dof;
  }
  if (x.pooled_expected >= 5.0) {
    x.chi2 += (x.pooled_observed - x.pooled_expected) * (x.pooled_observed - x.pooled_expected) / x.pooled_expected;
    ++x.dof;
    x.pooled_counted = true;
  }
  return x;
}

// A glass's albedo seen from wo, the red channel of f |cos_i| on the pairs it draws (drawn_eval)
// integrated over the charts of ior and alpha (the white furnaces' quadrature).
template <class Glass>
double drawn_albedo(const Glass& glass, const Vec3& wo, float ior, float alpha) {
  double sum = 0.0;
  for (double v : Charts(wo, ior, alpha).integrate_all([&](const Vec3& wi) { return drawn_eval(glass, wo, wi).x; }))
    sum += v;
  return sum;
}

// The chi-square test of a glass's sampling from wo against the density it states on the pairs it
// draws (drawn_pdf), binned on the charts of ior and alpha: the test, the density's total over the
// sphere (mass: at most about 1) and whether an uncounted pool of rare bins stays within bounds.
struct DielectricSampling {
  ChiSquare x;
  double mass = 0.0;
  bool rare_bins_ok = true;
};
template <class Glass>
DielectricSampling dielectric_sampling(const Glass& glass, const Vec3& wo, float ior, float alpha, Rng& rng,
                                       int samples) {
  const Charts charts(wo, ior, alpha);
  const std::vector<double> observed = sampled_bins(glass, wo, charts, rng, samples);
  DielectricSampling out;
  const std::vector<double> expected = expected_bins(
      charts, [&](const Vec3& wi) { return drawn_pdf(glass, wo, wi); }, samples, out.mass);
  out.x = pooled_chi_square(observed, expected);
  out.rare_bins_ok =
      out.x.pooled_counted || out.x.pooled_observed <= 5.0 + 10.0 * out.x.pooled_expected + 1e-4 * samples;
  return out;
}

}  // namespace torrance::test
