// Adaptive sampling, time limit and clamping (RenderSettings::adaptive_threshold, time_limit,
// clamp_direct/clamp_indirect), and the guarantee that set so that they cannot act they change
// nothing.
#include "torrance/integrator/integrator.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

namespace torrance {
namespace {

void add_quad(Scene& scene, uint32_t material, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const float v[] = {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z};
  const int64_t tris[] = {0, 1, 2, 0, 2, 3};
  const int64_t mats[] = {material, material};
  scene.add_mesh(v, 4, tris, 2, nullptr, mats);
}

Material lambert(float albedo) {
  Material m;
  m.base_color = Vec3(albedo);
  m.specular = 0.0f;
  m.roughness = 1.0f;
  return m;
}

// Seen from 5 m above (about 2 x 2 m): a floor on the left 60% under a uniform world, a point
// light with a radius and a glossy occluder above it (soft shadows, indirect light: noisy), and
// the bare world on the right (every sample the same: flat).
void build_mixed(Scene& scene) {
  const uint32_t floor = scene.add_material(lambert(0.5f));
  Material glossy;
  glossy.base_color = Vec3(0.8f, 0.6f, 0.3f);
  glossy.roughness = 0.2f;
  glossy.metallic = 1.0f;
  const uint32_t occluder = scene.add_material(glossy);
  add_quad(scene, floor, Vec3(-1.5f, -1.5f, 0), Vec3(0.2f, -1.5f, 0), Vec3(0.2f, 1.5f, 0), Vec3(-1.5f, 1.5f, 0));
  add_quad(scene, occluder, Vec3(-0.8f, -0.3f, 0.3f), Vec3(-0.8f, 0.3f, 0.3f), Vec3(-0.4f, 0.3f, 0.3f),
           Vec3(-0.4f, -0.3f, 0.3f));
  scene.lights().set_world(Vec3(0.5f), 1.0f);
  scene.lights().add_point(Vec3(-0.2f, 0.5f, 0.6f), 20.0f, Vec3(1.0f, 0.9f, 0.8f), 0.1f);
  CameraParams cam;
  cam.camera_to_world = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 5, 0, 0, 0, 1};
  cam.lens_mm = 90.0f;  // +-1 m at 5 m
  scene.set_camera(cam);
}

RenderSettings mixed_settings(int samples) {
  RenderSettings s;
  s.width = s.height = 64;
  s.samples = samples;
  return s;
}

double mean_sum(const Image& img) {
  double sum = 0.0;
  for (size_t i = 0; i < img.rgba.size(); i += 4) sum += double(img.rgba[i]) + img.rgba[i + 1] + img.rgba[i + 2];
  return sum / double(img.rgba.size() / 4);
}

// With adaptive sampling and the time limit off (their defaults) the renderer samples every
// pixel in full; set so that they can never act, they change nothing, bit for bit: not the
// image, not a pass, not the samples spent. The samples a pixel takes never depend on how the
// passes are cut (adaptive sampling ends passes at its checks, a time limit shrinks them), nor
// on the film adaptive sampling keeps. Clamping's "a limit nothing reaches" is in
// Clamping.BoundsEveryContributionAndZeroIsOff. (This replaces a hash of the image taken on one
// machine, which Embree's CPU-specific intersectors changed on another.)
TEST(AdaptiveSampling, LeversThatCannotActChangeNothing) {
  Scene scene;
  build_mixed(scene);
  RenderSettings s = mixed_settings(48);
  s.passes = kPassDiffuseDirect | kPassGlossyIndirect;
  const RenderResult off = render(scene, s);
  ASSERT_GE(off.samples_spent, uint64_t(64 * 64 * 48));  // and the splatted film's ring
  const auto same_as_off = [&](const RenderResult& r, const char* lever) {
    EXPECT_EQ(r.samples_spent, off.samples_spent) << lever;
    EXPECT_EQ(r.image.rgba, off.image.rgba) << lever;
    for (const char* pass : {"DiffDir", "GlossInd"})
      EXPECT_EQ(test::pass_named(r, pass).rgba, test::pass_named(off, pass).rgba) << lever << ", " << pass;
  };
  RenderSettings adaptive = s;  // checks would start after 48 samples: none is made
  adaptive.adaptive_threshold = 0.5f;
  adaptive.adaptive_min_samples = 48;
  same_as_off(render(scene, adaptive), "adaptive sampling with its minimum at the sample count");
  RenderSettings limited = s;
  limited.time_limit = 1e6;
  same_as_off(render(scene, limited), "a time limit of 11 days");
  RenderSettings one_sample_passes = s;
  one_sample_passes.pass_samples = 1;
  same_as_off(render(scene, one_sample_passes), "passes of one sample");
}

// Sums over seeds of the 8x8 block means (RGB summed) and of their squares; samples spent.
struct SeedStats {
  std::vector<double> sum, sum2;
  uint64_t spent = 0;
};

// The mean of each 8x8 block of the image's RGB (summed over channels), then the image mean last.
std::vector<double> block_means(const Image& img) {
  const int bw = img.width / 8, bh = img.height / 8;
  std::vector<double> out(size_t(bw) * bh + 1, 0.0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float* p = &img.rgba[(size_t(y) * img.width + x) * 4];
      const double v = double(p[0]) + p[1] + p[2];
      out[size_t(y / 8) * bw + x / 8] += v / 64.0;
      out.back() += v / (double(img.width) * img.height);
    }
  return out;
}

SeedStats render_seeds(Scene& scene, RenderSettings s, int seeds) {
  SeedStats st;
  for (int k = 0; k < seeds; ++k) {
    s.seed = uint32_t(k + 1);  // not seed 0
    const RenderResult r = render(scene, s);
    const std::vector<double> b = block_means(r.image);
    if (st.sum.empty()) st.sum.assign(b.size(), 0.0), st.sum2.assign(b.size(), 0.0);
    for (size_t i = 0; i < b.size(); ++i) st.sum[i] += b[i], st.sum2[i] += b[i] * b[i];
    st.spent += r.samples_spent;
    EXPECT_EQ(r.nonfinite_samples, 0u);
  }
  return st;
}

// Adaptive sampling converges to the plain render's image: the image mean and every 8x8 block
// mean agree within 4 standard errors (estimated from the spread over 6 seeds), while spending
// clearly fewer samples. Both films importance-sample the filter (as calibrated; the splatted
// film's adaptive sampling has its own test in test_filter_splatting.cpp).
TEST(AdaptiveSampling, AgreesWithPlainWithinNoiseAndSpendsFewerSamples) {
  Scene scene;
  build_mixed(scene);
  constexpr int kSeeds = 6;
  RenderSettings s = mixed_settings(256);
  s.filter_splatting = false;
  const SeedStats plain = render_seeds(scene, s, kSeeds);
  s.adaptive_threshold = 0.01f;
  const SeedStats adaptive = render_seeds(scene, s, kSeeds);
  const double ratio = double(adaptive.spent) / double(plain.spent);
  std::printf("adaptive / plain samples spent: %.3f\n", ratio);
  EXPECT_EQ(plain.spent, uint64_t(kSeeds) * 64 * 64 * 256);
  EXPECT_LT(ratio, 0.6);
  int worst = -1;
  double worst_z = 0.0;
  for (size_t i = 0; i < plain.sum.size(); ++i) {
    auto mean_var = [&](const SeedStats& st) {
      const double m = st.sum[i] / kSeeds;
      const double var = std::max(st.sum2[i] / kSeeds - m * m, 0.0) * kSeeds / (kSeeds - 1);
      return std::make_pair(m, var / kSeeds);  // the variance of the mean over seeds
    };
    const auto [mp, vp] = mean_var(plain);
    const auto [ma, va] = mean_var(adaptive);
    // Noise-free blocks (the bare world) must agree to float precision.
    const double z = std::abs(ma - mp) / (std::sqrt(vp + va) + 1e-6 * std::abs(mp) + 1e-9);
    if (z > worst_z) worst_z = z, worst = int(i);
    EXPECT_LT(z, 4.0) << (i + 1 == plain.sum.size() ? std::string("image mean") : "block " + std::to_string(i))
                      << ": plain " << mp << " adaptive " << ma;
  }
  std::printf("worst block %d: %.2f standard errors\n", worst, worst_z);
}

// The bare world (every sample identical) stops at the first check; the noisy floor goes on (the
// importance-sampled film's noise: with splatting's, about half, most of the floor stops there too).
TEST(AdaptiveSampling, FlatRegionsStopAtTheFirstCheck) {
  Scene scene;
  build_mixed(scene);
  RenderSettings s = mixed_settings(256);
  s.filter_splatting = false;
  s.adaptive_threshold = 0.01f;
  s.adaptive_min_samples = 16;
  // The glossy occluder's reflection of the lamp on the floor is part of the noise this test
  // needs; lights in mirrors would make it smooth (no pixel then needs all 256 samples).
  s.mirror_images = false;
  EXPECT_EQ(s.effective_adaptive_min_samples(), 16);
  const RenderResult r = render(scene, s);
  const auto count = [&](int x, int y) { return r.sample_counts.rgba[size_t(y) * 64 + x]; };
  ASSERT_EQ(r.sample_counts.width, 64);
  // Columns 56..63 see only the world, whatever the filter (the floor ends at x = 0.2 m, column 38).
  for (int y = 0; y < 64; ++y)
    for (int x = 56; x < 64; ++x) ASSERT_EQ(count(x, y), 32.0f) << x << ", " << y;  // min 16: checked at 32
  // The soft shadow and glossy occluder (columns 8..32, rows 16..48): most pixels go on, some to the end.
  int beyond_first_check = 0;
  float most = 0.0f;
  for (int y = 16; y < 48; ++y)
    for (int x = 8; x < 32; ++x) {
      beyond_first_check += count(x, y) > 32.0f;
      most = std::max(most, count(x, y));
    }
  std::printf("floor: %d of 768 pixels sampled beyond the first check, at most %g samples\n", beyond_first_check, most);
  EXPECT_GT(beyond_first_check, 768 / 4);
  EXPECT_EQ(most, 256.0f);
  double total = 0.0;
  for (float c : r.sample_counts.rgba) total += c;
  EXPECT_EQ(uint64_t(total), r.samples_spent);
  EXPECT_LT(r.samples_spent, uint64_t(64 * 64 * 256));
}

TEST(AdaptiveSampling, AutomaticMinimumSamplesAsCycles) {
  RenderSettings s;
  s.adaptive_threshold = 0.1f;
  EXPECT_EQ(s.effective_adaptive_min_samples(), 32);
  s.adaptive_threshold = 0.01f;
  EXPECT_EQ(s.effective_adaptive_min_samples(), 64);
  s.adaptive_threshold = 0.001f;
  EXPECT_EQ(s.effective_adaptive_min_samples(), 128);
  s.adaptive_min_samples = 2;
  EXPECT_EQ(s.effective_adaptive_min_samples(), 4);
  s.adaptive_threshold = -0.1f;
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s.adaptive_threshold = 0.0f;
  s.time_limit = -1.0;
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s.time_limit = 0.0;
  s.clamp_indirect = std::nanf("");
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

// Which pixels stop depends only on the samples, never on pass sizes or threads.
TEST(AdaptiveSampling, SameImageWhateverTheThreadCount) {
  Scene scene;
  build_mixed(scene);
  RenderSettings s = mixed_settings(128);
  s.adaptive_threshold = 0.02f;
  s.clamp_indirect = 1.0f;
  s.threads = 1;
  const RenderResult a = render(scene, s);
  s.threads = 2;
  const RenderResult b = render(scene, s);
  EXPECT_EQ(a.image.rgba, b.image.rgba);
  EXPECT_EQ(a.sample_counts.rgba, b.sample_counts.rgba);
  EXPECT_LT(a.samples_spent, uint64_t(64 * 64 * 128));
}

// A time limit ends the render with the pass that crosses it: the render took at least the limit
// and at most the limit plus one pass (passes aim at 0.5 s; with the limit near they shrink to it).
TEST(AdaptiveSampling, TimeLimitStopsWithinOnePassAfterTheLimit) {
  Scene scene;
  build_mixed(scene);
  RenderSettings s = mixed_settings(1 << 20);  // would take hours
  s.width = s.height = 128;
  s.time_limit = 1.0;
  std::vector<double> pass_times;
  const auto start = std::chrono::steady_clock::now();
  RenderCallbacks cb;
  cb.on_pass = [&](const Image&, int, int) {
    pass_times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  };
  const RenderResult r = render(scene, s, cb);
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(r.time_limit_reached);
  EXPECT_FALSE(r.stopped);
  EXPECT_LT(r.samples_done, s.samples);
  EXPECT_GE(total, s.time_limit);
  ASSERT_GE(pass_times.size(), 2u);
  // The pass before the last ended (and was delivered, within 50 ms) before the limit.
  EXPECT_LT(pass_times[pass_times.size() - 2], s.time_limit + 0.1);
  EXPECT_LT(total, s.time_limit + 0.6) << pass_times.size() << " passes";
  std::printf("time limit 1 s: %.3f s, %zu passes, %d samples\n", total, pass_times.size(), r.samples_done);
  // Without a limit the same render would go on: a short stop proves it.
  s.time_limit = 0.0;
  int passes = 0;
  cb.on_pass = [&](const Image&, int, int) { ++passes; };
  cb.should_stop = [&] { return passes >= 3; };
  const RenderResult unlimited = render(scene, s, cb);
  EXPECT_FALSE(unlimited.time_limit_reached);
  EXPECT_TRUE(unlimited.stopped);
}

// Fireflies: a floor lit by a point light 2 cm from a wall. The wall's light reaches the floor
// as indirect light (one NEE contribution per path with max_bounces 1), the floor's own light as
// direct (one NEE contribution per path: a point light of radius 0 is never hit). Clamping bounds
// each contribution's RGB sum, hence every pixel of the direct and indirect passes.
TEST(Clamping, BoundsEveryContributionAndZeroIsOff) {
  Scene scene;
  const uint32_t white = scene.add_material(lambert(0.8f));
  add_quad(scene, white, Vec3(-1.5f, -1.5f, 0), Vec3(1.5f, -1.5f, 0), Vec3(1.5f, 1.5f, 0), Vec3(-1.5f, 1.5f, 0));
  add_quad(scene, white, Vec3(0.5f, -1.5f, 0), Vec3(0.5f, 1.5f, 0), Vec3(0.5f, 1.5f, 1.5f), Vec3(0.5f, -1.5f, 1.5f));
  scene.lights().add_point(Vec3(0.48f, 0.0f, 0.3f), 200.0f, Vec3(1.0f, 0.8f, 0.6f), 0.0f);
  CameraParams cam;
  cam.camera_to_world = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 5, 0, 0, 0, 1};
  cam.lens_mm = 90.0f;
  scene.set_camera(cam);
  RenderSettings s = mixed_settings(16);
  s.max_bounces = 1;
  s.passes = kPassDiffuseDirect | kPassGlossyDirect | kPassDiffuseIndirect | kPassGlossyIndirect | kPassEmission |
             kPassEnvironment | kPassAlbedo | kPassGlossyColor;  // the colours: the light = pass x colour
  auto rgb_sum_max = [](const RenderResult& r, std::initializer_list<const char*> names) {
    double worst = 0.0;
    const size_t n = size_t(r.image.width) * r.image.height;
    std::vector<std::vector<float>> light;
    for (const char* name : names) light.push_back(test::undivided_pass(r, name));
    for (size_t i = 0; i < n; ++i) {
      double v = 0.0;
      for (const std::vector<float>& l : light) v += double(l[3 * i]) + l[3 * i + 1] + l[3 * i + 2];
      worst = std::max(worst, v);
    }
    return worst;
  };
  const RenderResult plain = render(scene, s);
  const double direct_max = rgb_sum_max(plain, {"DiffDir", "GlossDir", "Emit", "Env"});
  const double indirect_max = rgb_sum_max(plain, {"DiffInd", "GlossInd"});
  std::printf("unclamped: direct max %.2f, indirect max %.2f\n", direct_max, indirect_max);
  ASSERT_GT(direct_max, 20.0);
  ASSERT_GT(indirect_max, 2.0);  // fireflies

  s.clamp_direct = 3.0f;
  s.clamp_indirect = 0.5f;
  const RenderResult clamped = render(scene, s);
  EXPECT_LE(rgb_sum_max(clamped, {"DiffDir", "GlossDir", "Emit", "Env"}), 3.0 * (1 + 1e-5));
  EXPECT_LE(rgb_sum_max(clamped, {"DiffInd", "GlossInd"}), 0.5 * (1 + 1e-5));
  EXPECT_LT(mean_sum(clamped.image), mean_sum(plain.image));

  // Only the indirect limit: the direct light is untouched, bit for bit.
  s.clamp_direct = 0.0f;
  const RenderResult indirect_only = render(scene, s);
  EXPECT_EQ(test::pass_named(indirect_only, "DiffDir").rgba, test::pass_named(plain, "DiffDir").rgba);
  EXPECT_NE(indirect_only.image.rgba, plain.image.rgba);
  // 0 = off, and a limit nothing reaches changes nothing.
  s.clamp_indirect = 0.0f;
  EXPECT_EQ(render(scene, s).image.rgba, plain.image.rgba);
  s.clamp_direct = s.clamp_indirect = 1e30f;
  EXPECT_EQ(render(scene, s).image.rgba, plain.image.rgba);
}

}  // namespace
}  // namespace torrance
