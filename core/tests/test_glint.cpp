// The glint of a small sun in a near-mirror GGX lobe (issue 10): the reflected radiance that NEE
// of the sun's cone alone, BSDF sampling alone and their power-heuristic combination (weighed as
// the path tracer weighs them: the sun's sample pdf against the BSDF's, and a BSDF ray's sun hit
// pdf against it) estimate must agree, at grazing and moderate incidence, with the sun's disk
// centred on the mirror direction, on its edge and in the lobe's tail; and the combination must
// not be noisier than the better of the two alone (by more than a margin).
#include "torrance/lights/lights.h"
#include "torrance/bsdfs/principled.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace torrance {
namespace {

struct Estimate {
  double mean = 0.0, variance = 0.0;  // of one sample
};

template <typename F>
Estimate estimate(uint32_t n, uint32_t stream, F&& one_sample) {
  Rng rng(stream, 7, 3);
  double sum = 0.0, sum2 = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    const double v = one_sample(rng);
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n;
  return {mean, std::max(sum2 / n - mean * mean, 0.0)};
}

struct GlintCase {
  float cos_view;        // wo.z
  float offset_degrees;  // of the sun's centre from wo's mirror direction, in elevation
};

// A steel-like metal of roughness 0.06 (alpha 0.0036) under a 1-degree sun of strength 4.
void check_glint(const GlintCase& c) {
  Material m;
  m.base_color = Vec3(0.8f);
  m.metallic = 1.0f;
  m.roughness = 0.06f;
  const PrincipledBsdf bsdf(m);
  const Vec3 wo = test::direction(c.cos_view, 0.0f);
  const float elevation = std::asin(c.cos_view) + c.offset_degrees * kPi / 180.0f;
  const Vec3 to_sun = test::direction(std::sin(elevation), kPi);
  const SunLight sun(-to_sun, 4.0f, Vec3(1.0f), 1.0f * kPi / 180.0f);
  const Vec3 p(0.0f), n(0.0f, 0.0f, 1.0f);
  constexpr uint32_t kSamples = 1u << 19;

  auto nee = [&](Rng& rng, bool weighted) {
    const LightSample ls = sun.sample(p, n, rng.next_2d());
    if (!ls.valid() || ls.wi.z <= 0.0f) return 0.0;
    const float w = weighted ? power_heuristic(ls.pdf, bsdf.pdf(wo, ls.wi)) : 1.0f;
    return double(bsdf.eval(wo, ls.wi).x * ls.weight.x * w);
  };
  auto by_bsdf = [&](Rng& rng, bool weighted) {
    const float u_lobe = rng.next_1d();
    const BsdfSample bs = bsdf.sample(wo, u_lobe, rng.next_2d());
    LightHit hit;
    if (!bs.valid() || !sun.hit(p, n, bs.wi, std::numeric_limits<float>::infinity(), hit)) return 0.0;
    const float w = weighted ? power_heuristic(bs.pdf, hit.pdf) : 1.0f;
    return double(bs.weight.x * hit.radiance.x * w);
  };
  const Estimate e_nee = estimate(kSamples, 1, [&](Rng& r) { return nee(r, false); });
  const Estimate e_bsdf = estimate(kSamples, 2, [&](Rng& r) { return by_bsdf(r, false); });
  const Estimate e_mis = estimate(kSamples, 3, [&](Rng& r) { return nee(r, true) + by_bsdf(r, true); });

  const std::string what = "cos_view " + std::to_string(c.cos_view) + ", sun " + std::to_string(c.offset_degrees) +
                           " degrees off the mirror direction";
  std::printf("glint %s: NEE %.5g (var %.3g), BSDF %.5g (var %.3g), MIS %.5g (var %.3g)\n", what.c_str(), e_nee.mean,
              e_nee.variance, e_bsdf.mean, e_bsdf.variance, e_mis.mean, e_mis.variance);
  ASSERT_GT(e_mis.mean, 0.0) << what;
  auto standard_error = [&](const Estimate& e) { return std::sqrt(e.variance / kSamples); };
  for (const auto& [name, e] : {std::pair{"NEE", e_nee}, std::pair{"BSDF sampling", e_bsdf}}) {
    const double tolerance = 5.0 * std::hypot(standard_error(e), standard_error(e_mis)) + 1e-3 * e_mis.mean;
    EXPECT_NEAR(e.mean, e_mis.mean, tolerance) << name << " vs MIS, " << what;
  }
  EXPECT_LE(e_mis.variance, 1.5 * std::min(e_nee.variance, e_bsdf.variance) + 1e-6 * e_mis.mean * e_mis.mean)
      << "MIS is noisier than the better strategy, " << what << ": variances NEE " << e_nee.variance << ", BSDF "
      << e_bsdf.variance << ", MIS " << e_mis.variance;
}

TEST(Glint, NeeBsdfSamplingAndMisAgreeAtGrazingIncidence) {
  for (float offset : {0.0f, 0.5f, 1.5f}) check_glint({0.07f, offset});
}

TEST(Glint, NeeBsdfSamplingAndMisAgreeAtModerateIncidence) {
  for (float offset : {0.0f, 0.5f, 1.5f}) check_glint({0.5f, offset});
}

}  // namespace
}  // namespace torrance
