#include "test_helpers.h"

#include <gtest/gtest.h>

#include <set>

namespace torrance {
namespace {

TEST(Rng, SameStreamSameNumbersDifferentStreamsDiffer) {
  Rng a(12, 3, 7), b(12, 3, 7), c(12, 4, 7), d(12, 3, 8);
  const float x = a.next_1d();
  EXPECT_EQ(x, b.next_1d());
  EXPECT_NE(x, c.next_1d());
  EXPECT_NE(x, d.next_1d());
}

TEST(Rng, UniformMeanAndRange) {
  Rng rng(1, 2, 3);
  double sum = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const float u = rng.next_1d();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    sum += u;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.003);
}

TEST(Warps, CosineHemisphereHasMeanCosineTwoThirds) {
  Rng rng(5, 0, 0);
  double sum = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const Vec3 w = sample_cosine_hemisphere(rng.next_2d());
    ASSERT_NEAR(glm::length(w), 1.0f, 1e-4f);
    ASSERT_GT(w.z, 0.0f);
    sum += w.z;
  }
  EXPECT_NEAR(sum / n, 2.0 / 3.0, 0.003);
}

TEST(Warps, ConeSamplesStayInsideTinyAndWideCones) {
  Rng rng(9, 0, 0);
  for (float omc : {1e-6f, 1e-3f, 0.5f, 1.0f}) {
    for (int i = 0; i < 10000; ++i) {
      const Vec3 w = sample_uniform_cone(rng.next_2d(), omc);
      ASSERT_NEAR(glm::length(w), 1.0f, 1e-4f);
      ASSERT_LE(1.0f - w.z, omc * 1.001f + 1e-7f);
    }
  }
}

TEST(PixelFilter, SymmetricBoundedAndShapedLikeBlackmanHarris) {
  const PixelFilter filter(1.5f);
  EXPECT_NEAR(filter.sample_offset(0.5f), 0.0f, 1e-3f);
  EXPECT_NEAR(filter.sample_offset(0.0f), -1.5f, 1e-3f);
  EXPECT_NEAR(filter.sample_offset(0.999999f), 1.5f, 1e-2f);
  EXPECT_NEAR(filter.sample_offset(0.2f), -filter.sample_offset(0.8f), 1e-3f);
  // Blackman-Harris over +-1.5 px puts ~50% of its weight within +-0.36 px.
  const float q = filter.sample_offset(0.75f);
  EXPECT_GT(q, 0.25f);
  EXPECT_LT(q, 0.45f);
}

TEST(Mis, PowerHeuristicIsAPartitionOfUnity) {
  EXPECT_NEAR(power_heuristic(1.0f, 3.0f) + power_heuristic(3.0f, 1.0f), 1.0f, 1e-6f);
  EXPECT_EQ(power_heuristic(1.0f, 0.0f), 1.0f);
  EXPECT_EQ(power_heuristic(0.0f, 1.0f), 0.0f);
  EXPECT_EQ(power_heuristic(std::numeric_limits<float>::infinity(), 1.0f), 1.0f);
}

}  // namespace
}  // namespace torrance
