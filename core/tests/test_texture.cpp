// Image textures look up what Cycles' image texture node gives: sRGB images interpolated as
// stored and decoded after, and a pixel footprint's average equal to the average of those lookups.
#include "torrance/shader/texture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace torrance {
namespace {

double srgb_decode(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

// A grey checker of `squares` squares a side in n x n texels, sRGB-encoded values a and b.
std::vector<float> checker(int n, int squares, float a, float b) {
  std::vector<float> pixels(size_t(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) pixels[size_t(y) * n + x] = ((x * squares / n + y * squares / n) % 2 == 0) ? a : b;
  return pixels;
}

TEST(Texture, SrgbImagesAreInterpolatedAsStoredAndDecodedAfter) {
  const float texels[2] = {0.75f, 0.15f};
  const Texture tex(2, 1, 1, texels, ColorSpace::SRGB, Interpolation::Linear);
  // Halfway between the two texel centres (u = 0.5): the decoded mean of the encoded values.
  const float halfway = tex.lookup(Vec2(0.5f, 0.5f)).r;
  EXPECT_NEAR(halfway, srgb_decode(0.45), 1e-5);
  // Decoding first would give the mean of the decoded values, 0.27 instead of 0.171.
  EXPECT_GT(std::abs(halfway - 0.5 * (srgb_decode(0.75) + srgb_decode(0.15))), 0.05);
  // At a texel centre, the texel decoded; Closest decodes the texel too.
  EXPECT_NEAR(tex.lookup(Vec2(0.25f, 0.5f)).r, srgb_decode(0.75), 1e-5);
  const Texture closest(2, 1, 1, texels, ColorSpace::SRGB, Interpolation::Closest);
  EXPECT_NEAR(closest.lookup(Vec2(0.6f, 0.5f)).r, srgb_decode(0.15), 1e-6);
  // Alpha is not decoded; a linear image is interpolated linearly.
  EXPECT_FLOAT_EQ(tex.lookup(Vec2(0.5f, 0.5f)).a, 1.0f);
  const Texture linear(2, 1, 1, texels, ColorSpace::Linear, Interpolation::Linear);
  EXPECT_NEAR(linear.lookup(Vec2(0.5f, 0.5f)).r, 0.45, 1e-6);
}

TEST(Texture, FootprintAveragesWhatTheLookupsAverageTo) {
  const int n = 256;
  const std::vector<float> pixels = checker(n, 10, 0.75f, 0.15f);
  const Texture tex(n, n, 1, pixels.data(), ColorSpace::SRGB, Interpolation::Linear);
  // The mean of the finest-level lookups over the image, densely (8 x 8 points per texel) ...
  double dense = 0.0;
  const int m = 8 * n;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) dense += tex.lookup(Vec2((i + 0.5f) / m, (j + 0.5f) / m)).r;
  dense /= double(m) * m;
  // ... and the mean of the coarse level's lookups (footprint of 2 texels) over its texels.
  double coarse = 0.0;
  const int k = n / 2;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) coarse += tex.lookup(Vec2((i + 0.5f) / k, (j + 0.5f) / k), 2.0f / n).r;
  coarse /= double(k) * k;
  double decoded_texels = 0.0;
  for (float p : pixels) decoded_texels += srgb_decode(p);
  decoded_texels /= double(pixels.size());
  EXPECT_NEAR(coarse / dense, 1.0, 4e-4);
  EXPECT_GT(decoded_texels / dense, 1.015);  // what averaging decoded texels gave: 2 % bright
  // The whole-image average (the last level) too.
  EXPECT_NEAR(tex.lookup(Vec2(0.5f, 0.5f), 1.0e3f).r / dense, 1.0, 4e-4);
}

}  // namespace
}  // namespace torrance
