// GoogleTest checks of a whole material's BSDF shared by the layer tests (coat, sheen).
#pragma once

#include "torrance/bsdfs/material_bsdf.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance::test {

// Every sample of the prepared view v: its pdf is pdf(v, wi) and its weight eval / pdf (or a
// delta's reflectance).
inline void expect_samples_agree(const MaterialBsdf& bsdf, const MaterialBsdf::View& v) {
  Rng rng(7, 0, 99);
  for (int n = 0; n < 2000; ++n) {
    const float u = rng.next_1d();
    const BsdfSample s = bsdf.sample(v, u, rng.next_2d());
    if (!s.valid()) continue;
    ASSERT_TRUE(std::isfinite(s.weight.r) && std::isfinite(s.weight.g) && std::isfinite(s.weight.b));
    if (s.is_delta) continue;
    const float pdf = bsdf.pdf(v, s.wi);
    ASSERT_NEAR(s.pdf, pdf, 1e-4f * pdf);
    const Vec3 w = bsdf.eval_lobes(v, s.wi).total() / pdf;
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.weight[c], w[c], 1e-4f * std::max(w[c], 1.0f));
  }
}
inline void expect_samples_agree(const Material& m, BrdfModel model, const Vec3& wo) {
  const MaterialBsdf bsdf(m, model);
  expect_samples_agree(bsdf, bsdf.at(wo));
}

// eval, pdf and sample of n directions over the whole sphere seen from the prepared view v:
// finite, the pdf >= 0.
inline void expect_finite(const MaterialBsdf& bsdf, const MaterialBsdf::View& v, Rng& rng, int n = 500) {
  for (int k = 0; k < n; ++k) {
    const Vec3 wi = uniform_sphere(rng);
    const Vec3 f = bsdf.eval_lobes(v, wi).total();
    const float pdf = bsdf.pdf(v, wi);
    ASSERT_TRUE(std::isfinite(f.r) && std::isfinite(f.g) && std::isfinite(f.b) && std::isfinite(pdf));
    ASSERT_GE(pdf, 0.0f);
    const BsdfSample s = bsdf.sample(v, rng.next_1d(), rng.next_2d());
    ASSERT_TRUE(std::isfinite(s.weight.r) && std::isfinite(s.weight.g) && std::isfinite(s.weight.b));
    ASSERT_TRUE(std::isfinite(s.pdf));
  }
}
inline void expect_finite(const Material& m, BrdfModel model, const Vec3& wo, Rng& rng, int n = 500) {
  const MaterialBsdf bsdf(m, model);
  expect_finite(bsdf, bsdf.at(wo), rng, n);
}

}  // namespace torrance::test
