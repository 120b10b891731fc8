// Helpers shared by the core tests.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/integrator/integrator.h"
#include "torrance/util/math.h"
#include "torrance/util/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace torrance::test {

// A unit direction in the upper hemisphere with the given cosine and azimuth.
inline Vec3 direction(float cos_theta, float phi) {
  const float s = safe_sqrt(1.0f - cos_theta * cos_theta);
  return Vec3(s * std::cos(phi), s * std::sin(phi), cos_theta);
}

// Uniformly distributed unit vector on the sphere.
inline Vec3 uniform_sphere(Rng& rng) {
  const float z = 1.0f - 2.0f * rng.next_1d();
  return direction(z, kTwoPi * rng.next_1d());
}

// Every BRDF model, and its name as the module spells it.
inline constexpr BrdfModel kAllModels[] = {BrdfModel::Paper, BrdfModel::Principled, BrdfModel::PrincipledV2};
inline const char* model_name(BrdfModel m) {
  return m == BrdfModel::Paper ? "PAPER" : m == BrdfModel::Principled ? "PRINCIPLED" : "PRINCIPLED_V2";
}

// A render's pass by name (std::out_of_range if it was not rendered).
inline const Image& pass_named(const RenderResult& r, const std::string& name) {
  for (const auto& [pass, image] : r.passes)
    if (pass == name) return image;
  throw std::out_of_range("no pass " + name);
}

// A Direct/Indirect light pass times the colour pass the film divides it by (Albedo for the
// diffuse ones, GlossCol for the glossy ones; both rendered): the light it holds, as Combined
// sums it. Other passes as they are.
inline std::vector<float> undivided_pass(const RenderResult& r, const std::string& name) {
  std::vector<float> v = pass_named(r, name).rgba;
  const char* colour = name.rfind("Diff", 0) == 0 ? "Albedo" : name.rfind("Gloss", 0) == 0 ? "GlossCol" : nullptr;
  if (colour)
    for (size_t i = 0; i < v.size(); ++i) v[i] *= pass_named(r, colour).rgba[i];
  return v;
}

// Whether a (non-delta) sample s of bsdf from wo is what eval and pdf say: its pdf pdf(wo, wi)
// and its weight eval / pdf per channel, each to a relative `tolerance`.
template <typename Bsdf>
::testing::AssertionResult sample_matches_eval(const Bsdf& bsdf, const Vec3& wo, const BsdfSample& s,
                                               float tolerance = 2e-3f) {
  if (s.is_delta) return ::testing::AssertionFailure() << "a delta sample";
  const float pdf = bsdf.pdf(wo, s.wi);
  const Vec3 f = bsdf.eval(wo, s.wi);
  if (!(std::abs(s.pdf - pdf) <= tolerance * pdf))
    return ::testing::AssertionFailure() << "sample pdf " << s.pdf << ", pdf() " << pdf;
  for (int k = 0; k < 3; ++k)
    if (!(std::abs(s.weight[k] - f[k] / pdf) <= tolerance * f[k] / pdf + 1e-6f))
      return ::testing::AssertionFailure() << "channel " << k << " weight " << s.weight[k] << ", eval / pdf "
                                           << f[k] / pdf;
  return ::testing::AssertionSuccess();
}

// The mean red weight of n samples of a BSDF (anything with sample(wo, u_lobe, u)) for wo: its
// albedo there, as a white furnace sees it.
template <typename Bsdf>
double mean_sample_weight(const Bsdf& bsdf, const Vec3& wo, int n, uint32_t seed) {
  Rng rng(seed, 0, 99);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const float u = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, u, rng.next_2d());
    if (s.valid()) sum += s.weight.x;
  }
  return sum / n;
}

// A rough glass's pdf and eval on the pairs of directions its sampling draws: 0 on the refraction
// pairs no microfacet connects, which it values as Cycles does but never draws (connects(),
// refraction_pair.h). For the checks of sampling against pdf and eval.
template <typename Glass>
float drawn_pdf(const Glass& glass, const Vec3& wo, const Vec3& wi) {
  return glass.connects(wo, wi) ? glass.pdf(wo, wi) : 0.0f;
}
template <typename Glass>
Vec3 drawn_eval(const Glass& glass, const Vec3& wo, const Vec3& wi) {
  return glass.connects(wo, wi) ? glass.eval(wo, wi) : Vec3(0.0f);
}

}  // namespace torrance::test
