// Splatting samples into every pixel their filter covers (RenderSettings::filter_splatting,
// film.h): the splatted film converges to the filter-importance-sampled one (Cycles' way), at its
// edges too (the ring of pixels sampled around the image), is exact on flat regions at one sample,
// has clearly less noise per pixel, does not depend on the threads, and is used only where it can.
#include "torrance/integrator/integrator.h"
#include "scene_helpers.h"
#include <gtest/gtest.h>
#include <cstring>
#include <vector>

namespace torrance {
namespace {

// A sunlit checkerboard of 10 cm squares (about 1.5 pixels each in a 32 x 32 image) filling the
// view (or its left half, the bare sky beside it): every pixel's value depends on where in it (and
// beyond it) its samples land.
void build_checkerboard(Scene& scene, bool left_half_only = false) {
  const int64_t light = scene.add_material(test::diffuse_material(Vec3(0.8f)));
  const int64_t dark = scene.add_material(test::diffuse_material(Vec3(0.05f)));
  constexpr float kSquare = 0.1f;
  for (int j = -16; j < 16; ++j)
    for (int i = -16; i < (left_half_only ? 0 : 16); ++i) {
      const float x0 = i * kSquare, y0 = j * kSquare, x1 = x0 + kSquare, y1 = y0 + kSquare;
      test::add_quad(scene, {x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}, (i + j) % 2 ? dark : light);
    }
  scene.lights().add_sun(glm::normalize(Vec3(0.3f, 0.5f, -1.0f)), 3.0f, Vec3(1.0f), 0.01f);
  scene.lights().set_world(Vec3(1.0f), left_half_only ? 1.0f : 0.05f);  // a bright sky beside a half board
  test::look_down(scene, 3.0f, 50.0f);  // 2.16 m across
}

// A dark square exactly filling the 32 x 32 view, in a bright surround: every edge pixel's
// filter reaches the bright ground just beyond the image.
void build_bright_frame(Scene& scene) {
  const int64_t light = scene.add_material(test::diffuse_material(Vec3(0.8f)));
  const int64_t dark = scene.add_material(test::diffuse_material(Vec3(0.05f)));
  constexpr float kEdge = 1.08f, kOut = 3.0f;  // the view's half-width: 3 m x 18 mm / 50 mm
  test::add_quad(scene, {-kEdge, -kEdge, 0}, {kEdge, -kEdge, 0}, {kEdge, kEdge, 0}, {-kEdge, kEdge, 0}, dark);
  test::add_quad(scene, {-kOut, -kOut, 0}, {kOut, -kOut, 0}, {kOut, -kEdge, 0}, {-kOut, -kEdge, 0}, light);
  test::add_quad(scene, {-kOut, kEdge, 0}, {kOut, kEdge, 0}, {kOut, kOut, 0}, {-kOut, kOut, 0}, light);
  test::add_quad(scene, {-kOut, -kEdge, 0}, {-kEdge, -kEdge, 0}, {-kEdge, kEdge, 0}, {-kOut, kEdge, 0}, light);
  test::add_quad(scene, {kEdge, -kEdge, 0}, {kOut, -kEdge, 0}, {kOut, kEdge, 0}, {kEdge, kEdge, 0}, light);
  scene.lights().add_sun(Vec3(0.0f, 0.0f, -1.0f), 3.0f, Vec3(1.0f), 0.01f);
  test::look_down(scene, 3.0f, 50.0f);
}

RenderSettings settings(uint32_t seed, bool splatting, int samples = 16) {
  RenderSettings s;
  s.width = s.height = 32;
  s.samples = samples;
  s.seed = seed;
  s.max_bounces = 1;
  s.filter_splatting = splatting;
  return s;
}

// The green channel's mean over each column of the image.
std::vector<double> column_means(const Image& img) {
  std::vector<double> columns(size_t(img.width), 0.0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) columns[size_t(x)] += img.rgba[(size_t(y) * img.width + x) * 4 + 1] / img.height;
  return columns;
}

// The green channel along the image's border, in 16 runs of 8 pixels (4 per edge).
std::vector<double> border_runs(const Image& img) {
  std::vector<double> runs;
  auto g = [&](int x, int y) { return double(img.rgba[(size_t(y) * img.width + x) * 4 + 1]); };
  for (int k = 0; k < 4; ++k) {
    double top = 0, bottom = 0, left = 0, right = 0;
    for (int i = 8 * k; i < 8 * k + 8; ++i) {
      top += g(i, 0) / 8;
      bottom += g(i, img.height - 1) / 8;
      left += g(0, i) / 8;
      right += g(img.width - 1, i) / 8;
    }
    runs.insert(runs.end(), {top, bottom, left, right});
  }
  return runs;
}

// Both films over 12 seeds: the image, its 8 x 8 blocks and the border's runs agree within noise,
// and the splatted pixels' variance is well under the importance-sampled ones'.
TEST(FilterSplatting, AgreesWithFilterImportanceSamplingAndHasLessNoise) {
  Scene scene;
  build_checkerboard(scene);
  std::vector<std::vector<double>> fis_blocks, splat_blocks, fis_border, splat_border;
  std::vector<Image> fis, splat;
  for (uint32_t seed = 10; seed < 22; ++seed) {
    const RenderResult a = render(scene, settings(seed, false));
    const RenderResult b = render(scene, settings(seed + 100, true));
    ASSERT_FALSE(a.filter_splatting);
    ASSERT_TRUE(b.filter_splatting);
    EXPECT_EQ(b.nonfinite_samples, 0u);
    fis.push_back(a.image);
    splat.push_back(b.image);
    fis_blocks.push_back(test::block_means_32(a.image));
    splat_blocks.push_back(test::block_means_32(b.image));
    fis_border.push_back(border_runs(a.image));
    splat_border.push_back(border_runs(b.image));
  }
  const test::SeedAgreement blocks = test::compare_over_seeds(fis_blocks, splat_blocks);
  const test::SeedAgreement border = test::compare_over_seeds(fis_border, splat_border);
  std::printf("blocks: ratio %.4f, image z %.2f, worst block z %.2f; border: worst run z %.2f\n", blocks.ratio,
              blocks.image_z, blocks.worst_block_z, border.worst_block_z);
  test::expect_agreement(blocks, 0.01);
  EXPECT_LT(border.worst_block_z, 4.5);
  const double ratio = test::mean_pixel_variance(splat) / test::mean_pixel_variance(fis);
  std::printf("pixel variance, splatted / importance-sampled: %.3f\n", ratio);
  EXPECT_LT(ratio, 0.6);
}

// The image's edge pixels take the samples of the ring around it: against a bright surround
// just beyond a dark image, the splatted edges agree with the importance-sampled ones (whose
// samples land beyond the edge by the filter's own density).
TEST(FilterSplatting, EdgePixelsSeeTheFilterBeyondTheImage) {
  Scene scene;
  build_bright_frame(scene);
  std::vector<std::vector<double>> fis_border, splat_border;
  for (uint32_t seed = 10; seed < 18; ++seed) {
    fis_border.push_back(border_runs(render(scene, settings(seed, false, 8)).image));
    splat_border.push_back(border_runs(render(scene, settings(seed + 100, true, 8)).image));
  }
  const test::SeedAgreement border = test::compare_over_seeds(fis_border, splat_border);
  std::printf("border: ratio %.4f, worst run z %.2f\n", border.ratio, border.worst_block_z);
  EXPECT_NEAR(border.ratio, 1.0, 0.02);
  EXPECT_LT(border.worst_block_z, 4.5);
}

// A pixel is the weighted mean of the samples that reach it, so where every sample brings the
// same value (a uniform world) every pixel is that value at one sample, like the importance-
// sampled film: a film divided by the expected weight instead would be noisy there.
TEST(FilterSplatting, FlatRegionsAreExactAtOneSample) {
  Scene scene;
  scene.lights().set_world(Vec3(0.25f, 0.5f, 0.75f), 1.0f);
  test::look_down(scene, 3.0f, 50.0f);
  for (uint32_t seed : {1u, 2u}) {
    const RenderResult r = render(scene, settings(seed, true, 1));
    ASSERT_TRUE(r.filter_splatting);
    for (size_t i = 0; i < r.image.rgba.size(); i += 4) {
      ASSERT_NEAR(r.image.rgba[i], 0.25f, 1e-6f) << "pixel " << i / 4;
      ASSERT_NEAR(r.image.rgba[i + 1], 0.5f, 1e-6f) << "pixel " << i / 4;
      ASSERT_NEAR(r.image.rgba[i + 2], 0.75f, 1e-6f) << "pixel " << i / 4;
      ASSERT_NEAR(r.image.rgba[i + 3], 1.0f, 1e-6f) << "pixel " << i / 4;
    }
  }
}

// Each pixel's sums take their samples in the same order (the tiles' phases, then each tile's
// rows) however many threads run the tiles: one thread or two, the same image bit for bit. (The
// phases also keep tiles that splat into the same pixels from running at once; a race is too
// rare at this size for a test to catch: with every tile in one phase this still passed 3 of 3.)
TEST(FilterSplatting, ThreadsGiveTheSameImage) {
  Scene scene;
  build_checkerboard(scene);
  RenderSettings s = settings(3, true, 8);
  s.width = 80;  // several tiles each way
  s.height = 48;
  s.passes = kPassDiffuseDirect | kPassNormal;
  s.threads = 1;
  const RenderResult one = render(scene, s);
  s.threads = 2;
  const RenderResult two = render(scene, s);
  ASSERT_TRUE(one.filter_splatting);
  EXPECT_EQ(std::memcmp(one.image.rgba.data(), two.image.rgba.data(), one.image.rgba.size() * 4), 0);
  ASSERT_EQ(one.passes.size(), two.passes.size());
  for (size_t p = 0; p < one.passes.size(); ++p)
    EXPECT_EQ(std::memcmp(one.passes[p].second.rgba.data(), two.passes[p].second.rgba.data(),
                          one.passes[p].second.rgba.size() * 4), 0)
        << one.passes[p].first;
  EXPECT_EQ(one.samples_spent, uint64_t(82 * 50 * 8));  // the image and its 1-pixel ring
}

// Adaptive sampling on a splatted film: where the checkerboard meets the bare sky, the sky's pixels
// stop at the first check while the board's go on; a pixel takes splats only while its 3 x 3
// neighbourhood is sampled, so its weighted mean stays that of an evenly sampled neighbourhood.
// Over 16 seeds the image agrees with the plain splatted render block by block and column by
// column (worst column 2.37 standard errors), for fewer samples. Splatting into every pixel
// regardless (the sky's pixels at the edge then weigh the board's later samples more than their
// own side's) moves the edge's columns: 6.19 standard errors, and the test fails.
TEST(FilterSplatting, AdaptiveSamplingAgreesWithThePlainRender) {
  Scene scene;
  build_checkerboard(scene, true);
  std::vector<std::vector<double>> plain_blocks, adaptive_blocks, plain_columns, adaptive_columns;
  uint64_t plain_spent = 0, adaptive_spent = 0;
  float fewest = 1e9f, most = 0.0f;
  for (uint32_t seed = 10; seed < 26; ++seed) {
    RenderSettings s = settings(seed, true, 128);
    const RenderResult p = render(scene, s);
    plain_blocks.push_back(test::block_means_32(p.image));
    plain_columns.push_back(column_means(p.image));
    plain_spent += p.samples_spent;
    s.seed = seed + 100;
    s.adaptive_threshold = 0.004f;
    s.adaptive_min_samples = 16;
    const RenderResult a = render(scene, s);
    ASSERT_TRUE(a.filter_splatting);
    adaptive_blocks.push_back(test::block_means_32(a.image));
    adaptive_columns.push_back(column_means(a.image));
    adaptive_spent += a.samples_spent;
    for (float c : a.sample_counts.rgba) fewest = std::min(fewest, c), most = std::max(most, c);
  }
  const test::SeedAgreement agreement = test::compare_over_seeds(plain_blocks, adaptive_blocks);
  const test::SeedAgreement columns = test::compare_over_seeds(plain_columns, adaptive_columns);
  std::printf("adaptive / plain: ratio %.4f, image z %.2f, worst block z %.2f, worst column z %.2f; samples %.3f, "
              "%g to %g per pixel\n",
              agreement.ratio, agreement.image_z, agreement.worst_block_z, columns.worst_block_z,
              double(adaptive_spent) / plain_spent, fewest, most);
  EXPECT_LT(columns.worst_block_z, 4.5);
  EXPECT_EQ(fewest, 32.0f);  // the sky: stopped at the first check
  EXPECT_EQ(most, 128.0f);   // parts of the board: every sample
  EXPECT_LT(double(adaptive_spent), 0.8 * double(plain_spent));
  test::expect_agreement(agreement, 0.01);
}

// Splatting needs a filter between 1 and 2.5 pixels wide (with adaptive sampling, whose stopped
// pixels are 1 pixel apart from the sampled ones, at most 1.5); elsewhere the film draws samples
// by the filter's importance.
TEST(FilterSplatting, UsedOnlyWhereItCan) {
  Scene scene;
  build_checkerboard(scene);
  auto splats = [&](auto edit) {
    RenderSettings s = settings(1, true, 2);
    s.width = s.height = 8;
    edit(s);
    return render(scene, s).filter_splatting;
  };
  EXPECT_TRUE(splats([](RenderSettings&) {}));
  EXPECT_TRUE(splats([](RenderSettings& s) { s.filter_width = 1.0f; }));
  EXPECT_TRUE(splats([](RenderSettings& s) { s.filter_width = 2.5f; }));
  EXPECT_FALSE(splats([](RenderSettings& s) { s.filter_splatting = false; }));
  EXPECT_TRUE(splats([](RenderSettings& s) { s.adaptive_threshold = 0.01f; }));
  EXPECT_FALSE(splats([](RenderSettings& s) { s.adaptive_threshold = 0.01f, s.filter_width = 2.0f; }));
  EXPECT_FALSE(splats([](RenderSettings& s) { s.filter_width = 0.5f; }));
  EXPECT_FALSE(splats([](RenderSettings& s) { s.filter_width = 3.0f; }));
}

}  // namespace
}  // namespace torrance
