// Blender 4.x's Voronoi Texture (core/src/shader/shader_voronoi4.cpp) as Cycles 4.x computes it: one
// octave is Cycles 3.4's node (to a float's rounding: 4.x multiplies by 1 / Scale), Detail's
// octaves are the sums shader_voronoi.h describes, Normalize keeps F1's distance within [0, 1].
// The Python twin's test (core/python/tests/test_shader_voronoi4_ops.py) checks the op bit for
// bit against voronoi4.py; test_shader_voronoi_agreement against Cycles 4.2.
#include "torrance/shader/shader_voronoi.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace torrance {
namespace {

using shader::VoronoiFeature;
using shader::VoronoiFractal;
using shader::VoronoiInputs;
using shader::VoronoiMetric;
using shader::VoronoiSettings;

VoronoiInputs random_inputs(std::mt19937& rng) {
  std::uniform_real_distribution<float> coordinate(-20.0f, 20.0f), unit(0.0f, 1.0f);
  VoronoiInputs in;
  in.vector = Vec3(coordinate(rng), coordinate(rng), coordinate(rng));
  in.w = coordinate(rng);
  in.scale = 0.5f + 3.0f * unit(rng);
  in.smoothness = 0.2f + unit(rng);
  in.exponent = 0.5f + 2.0f * unit(rng);
  in.randomness = unit(rng);
  return in;
}

TEST(ShaderVoronoi4, OneOctaveIsCycles34sNode) {
  std::mt19937 rng(3);
  for (int mode = 0; mode < shader::kVoronoiModes; ++mode) {
    const VoronoiSettings s = shader::voronoi_settings(mode);
    for (int i = 0; i < 20; ++i) {
      const VoronoiInputs in = random_inputs(rng);
      const auto old = shader::voronoi(s, in);
      const auto now = shader::voronoi4(s, in, VoronoiFractal{});  // Detail 0
      EXPECT_NEAR(now.distance, old.distance, 1e-5f) << mode;
      EXPECT_NEAR(now.radius, old.radius, 1e-5f) << mode;
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(now.color[k], old.color[k], 1e-5f) << mode;
        EXPECT_NEAR(now.position[k], old.position[k], 1e-5f * (1.0f + std::fabs(old.position[k]))) << mode;
      }
      EXPECT_NEAR(now.w, old.w, 1e-5f * (1.0f + std::fabs(old.w))) << mode;
    }
  }
}

TEST(ShaderVoronoi4, OctavesAreWeightedSums) {
  const VoronoiSettings s{3, VoronoiFeature::F1, VoronoiMetric::Euclidean};
  VoronoiInputs in;
  in.vector = Vec3(0.31f, -0.72f, 0.45f);
  in.scale = 1.0f;
  VoronoiInputs far = in;
  far.vector = in.vector * 2.5f;
  const float first = shader::voronoi4(s, in, {}).distance, second = shader::voronoi4(s, far, {}).distance;
  EXPECT_NEAR(shader::voronoi4(s, in, {1.0f, 0.4f, 2.5f, false}).distance, first + 0.4f * second, 1e-6f);
  EXPECT_NEAR(shader::voronoi4(s, in, {0.5f, 0.4f, 2.5f, false}).distance, first + 0.2f * second, 1e-6f);
  EXPECT_NEAR(shader::voronoi4(s, in, {1.0f, 0.4f, 2.5f, true}).distance,
              (first + 0.4f * second) / (1.4f * std::sqrt(3.0f)), 1e-6f);
}

TEST(ShaderVoronoi4, NormalizedF1StaysWithinOne) {
  std::mt19937 rng(5);
  for (int d = 1; d <= 4; ++d)
    for (int m = 0; m < 3; ++m) {
      const VoronoiSettings s{d, VoronoiFeature::F1, VoronoiMetric(m)};
      for (int i = 0; i < 100; ++i) {
        const float distance = shader::voronoi4(s, random_inputs(rng), {3.5f, 0.7f, 2.0f, true}).distance;
        EXPECT_GE(distance, 0.0f);
        EXPECT_LE(distance, 1.0f + 1e-6f) << d << "D metric " << m;
      }
    }
}

}  // namespace
}  // namespace torrance
