// Blender 4.3+'s Gabor Texture (core/src/shader/shader_gabor.cpp) as Cycles computes it: the three
// outputs are one phasor's imaginary part, angle and length; the node's inputs are clamped and
// normalised as Cycles does; the noise is centred on 1/2. The Python twin's test
// (core/python/tests/test_shader_gabor_ops.py) checks the op against gabor.py;
// test_shader_gabor_agreement against Cycles 4.5 and 5.3.
#include "torrance/shader/shader_gabor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace torrance {
namespace {

using shader::GaborInputs;
using shader::GaborOutputs;
using shader::GaborType;

bool same(const GaborOutputs& a, const GaborOutputs& b) {
  return a.value == b.value && a.phase == b.phase && a.intensity == b.intensity;
}

TEST(ShaderGabor, OutputsAreOnePhasor) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> coordinate(-5.0f, 5.0f), unit(0.0f, 1.0f);
  for (int k = 0; k < 40; ++k) {
    GaborInputs in;
    in.vector = Vec3(coordinate(rng), coordinate(rng), coordinate(rng));
    in.scale = 1.0f + unit(rng);
    in.anisotropy = unit(rng);
    const GaborOutputs out = shader::gabor_texture(GaborType(k % 2), in);
    ASSERT_GE(out.phase, 0.0f);
    ASSERT_LE(out.phase, 1.0f);
    ASSERT_GE(out.intensity, 0.0f);
    const double angle = 2.0 * M_PI * out.phase - M_PI;
    EXPECT_NEAR(out.value - 0.5, 0.5 * out.intensity * std::sin(angle), 2e-6) << k;
  }
}

TEST(ShaderGabor, InputsAsCyclesReadsThem) {
  for (GaborType type : {GaborType::TwoD, GaborType::ThreeD}) {
    GaborInputs in;
    in.vector = Vec3(0.37f, -1.2f, 2.6f);
    auto at = [&](auto&& edit) {
      GaborInputs changed = in;
      edit(changed);
      return shader::gabor_texture(type, changed);
    };
    const GaborOutputs base = shader::gabor_texture(type, in);
    EXPECT_TRUE(same(at([](GaborInputs& c) { c.anisotropy = 1.7f; }), base));
    EXPECT_TRUE(same(at([](GaborInputs& c) { c.anisotropy = -0.4f; }),
                     at([](GaborInputs& c) { c.anisotropy = 0.0f; })));
    EXPECT_TRUE(same(at([](GaborInputs& c) { c.frequency = -3.0f; }),
                     at([](GaborInputs& c) { c.frequency = 0.001f; })));
    EXPECT_TRUE(same(at([](GaborInputs& c) { c.scale = 2.0f; }), at([](GaborInputs& c) {
                       c.vector *= 2.0f;
                       c.scale = 1.0f;
                     })));
    // 2D reads the Vector's x and y only, 3D its z too.
    const GaborOutputs moved_z = at([](GaborInputs& c) { c.vector.z = -7.0f; });
    EXPECT_EQ(same(moved_z, base), type == GaborType::TwoD);
  }
  GaborInputs in;
  in.anisotropy = 0.4f;
  in.orientation_3d = Vec3(0.0f, 3.0f, 4.0f);
  GaborInputs unit = in;
  unit.orientation_3d = Vec3(0.0f, 0.6f, 0.8f);
  EXPECT_TRUE(same(shader::gabor_texture(GaborType::ThreeD, in), shader::gabor_texture(GaborType::ThreeD, unit)));
}

TEST(ShaderGabor, NoiseIsCentred) {
  for (GaborType type : {GaborType::TwoD, GaborType::ThreeD}) {
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> coordinate(-20.0f, 20.0f);
    double sum = 0.0, sum2 = 0.0;
    const int n = 400;
    for (int k = 0; k < n; ++k) {
      GaborInputs in;
      in.vector = Vec3(coordinate(rng), coordinate(rng), coordinate(rng));
      in.scale = 1.0f;
      in.anisotropy = 0.5f;
      const float v = shader::gabor_texture(type, in).value;
      ASSERT_GT(v, 0.0f);
      ASSERT_LT(v, 1.0f);
      sum += v;
      sum2 += double(v) * v;
    }
    const double mean = sum / n, deviation = std::sqrt(sum2 / n - mean * mean);
    EXPECT_NEAR(mean, 0.5, 0.015);
    EXPECT_GT(deviation, 0.03);
  }
}

}  // namespace
}  // namespace torrance
