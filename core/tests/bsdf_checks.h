// GoogleTest checks of a whole material's BSDF shared by the layer tests (coat, sheen).
#pragma once

#include "torrance/bsdfs/material_bsdf.h"

#include "test_helpers.h"

#include <gtest/gtest.h>

namespace torrance::test {

// Every sample: its pdf is pdf(wo, wi) and its weight eval / pdf (or a delta's reflectance).
inline void expect_samples_agree(const Material& m, BrdfModel model, const Vec3& wo) {
  const MaterialBsdf bsdf(m, model);
  Rng rng(7, 0, 99);
  for (int n = 0; n < 2000; ++n) {
    const float u = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, u, rng.next_2d());
    if (!s.valid()) continue;
    ASSERT_TRUE(std::isfinite(s.weight.r) && std::isfinite(s.weight.g) && std::isfinite(s.weight.b));
    if (s.is_delta) continue;
    const float pdf = bsdf.pdf(wo, s.wi);
    ASSERT_NEAR(s.pdf, pdf, 1e-4f * pdf);
    const Vec3 w = bsdf.eval(wo, s.wi) / pdf;
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.weight[c], w[c], 1e-4f * std::max(w[c], 1.0f));
  }
}

// eval, pdf and sample of n directions over the whole sphere: finite, the pdf >= 0.
inline void expect_finite(const Material& m, BrdfModel model, const Vec3& wo, Rng& rng, int n = 500) {
  const MaterialBsdf bsdf(m, model);
  for (int k = 0; k < n; ++k) {
    const Vec3 wi = uniform_sphere(rng);
    const Vec3 f = bsdf.eval(wo, wi);
    const float pdf = bsdf.pdf(wo, wi);
    ASSERT_TRUE(std::isfinite(f.r) && std::isfinite(f.g) && std::isfinite(f.b) && std::isfinite(pdf));
    ASSERT_GE(pdf, 0.0f);
    const BsdfSample s = bsdf.sample(wo, rng.next_1d(), rng.next_2d());
    ASSERT_TRUE(std::isfinite(s.weight.r) && std::isfinite(s.weight.g) && std::isfinite(s.weight.b));
    ASSERT_TRUE(std::isfinite(s.pdf));
  }
}

}  // namespace torrance::test
