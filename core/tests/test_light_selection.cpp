// Choosing one light for next-event estimation among many (Lights::select, LightChoice): the
// probability reported is the frequency with which each light is chosen, and NEE through the
// choice is unbiased.
#include "scene_helpers.h"
#include "test_helpers.h"
#include "torrance/integrator/integrator.h"
#include "torrance/lights/light_choice.h"
#include "torrance/lights/lights.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <new>
#include <vector>

namespace torrance {
namespace {

using test::uniform_sphere;

// Dozens of lights of every kind around the origin, from one seed: points (delta and with a
// radius), spots and areas (squares and disks), powers over two decades.
Lights many_lights(uint32_t seed, int count) {
  Lights lights;
  Rng rng(0, 0, seed);
  auto in_box = [&](float half) {
    return Vec3((2.0f * rng.next_1d() - 1.0f) * half, (2.0f * rng.next_1d() - 1.0f) * half, 0.2f + 2.0f * rng.next_1d());
  };
  for (int i = 0; i < count; ++i) {
    const Vec3 at = in_box(3.0f);
    const float power = std::pow(10.0f, 2.0f * rng.next_1d());
    const Vec3 color(0.3f + 0.7f * rng.next_1d(), 0.3f + 0.7f * rng.next_1d(), 0.3f + 0.7f * rng.next_1d());
    switch (i % 4) {
      case 0: lights.add_point(at, power, color, 0.0f); break;
      case 1: lights.add_point(at, power, color, 0.02f + 0.1f * rng.next_1d()); break;
      case 2: lights.add_spot(at, Vec3(0.3f, -0.2f, -1.0f) + 0.3f * uniform_sphere(rng), power, color, 0.05f, 1.0f, 0.3f); break;
      default: {
        const float size = 0.1f + 0.4f * rng.next_1d();
        lights.add_area(at, Vec3(size, 0, 0), Vec3(0, size, 0), Vec3(0.2f, 0.1f, -1.0f), i % 8 == 7, power, color, kPi);
      }
    }
  }
  return lights;
}

// Shading points on a floor and on walls facing every way, with their normals.
std::vector<std::pair<Vec3, Vec3>> shading_points(uint32_t seed, int count) {
  Rng rng(0, 0, seed);
  std::vector<std::pair<Vec3, Vec3>> points;
  for (int i = 0; i < count; ++i) {
    const Vec3 p((2.0f * rng.next_1d() - 1.0f) * 3.0f, (2.0f * rng.next_1d() - 1.0f) * 3.0f, 0.5f * rng.next_1d());
    Vec3 n = i % 2 == 0 ? Vec3(0, 0, 1) : uniform_sphere(rng);
    points.emplace_back(p, n);
  }
  return points;
}

TEST(LightSelection, ChoosesEachLightAsOftenAsItsProbabilitySays) {
  const Lights lights = many_lights(7, 48);
  constexpr int kDraws = 20000;
  for (const LightSelection mode : {LightSelection::Uniform, LightSelection::Contribution}) {
    Lights l = lights;
    l.set_selection(mode);
    for (const auto& [p, n] : shading_points(3, 12)) {
      std::vector<int> chosen(l.count(), 0);
      for (int i = 0; i < kDraws; ++i) {
        const Lights::Choice c = l.select(p, n, (i + 0.5f) / kDraws);
        ASSERT_LT(c.index, l.count());
        ASSERT_GT(c.probability, 0.0f);
        EXPECT_NEAR(c.probability, l.selection_probability(c.index, p, n), 1e-6f * c.probability + 1e-9f);
        ++chosen[c.index];
      }
      float total = 0.0f;
      for (size_t k = 0; k < l.count(); ++k) {
        const float prob = l.selection_probability(k, p, n);
        total += prob;
        // Stratified draws: each light's count is within one draw of kDraws x its probability.
        EXPECT_NEAR(chosen[k], kDraws * prob, 1.5f) << "light " << k;
      }
      EXPECT_NEAR(total, 1.0f, 1e-4f);
    }
  }
}

// Irradiance on a surface from delta point lights and spots has a closed form; one-light NEE
// (choice, then the light's own sample) must average to it whatever the selection.
TEST(LightSelection, NextEventEstimationIsUnbiased) {
  Lights lights;
  Rng rng(0, 0, 11);
  struct Delta {
    Vec3 at, intensity;
  };
  std::vector<Delta> deltas;
  for (int i = 0; i < 40; ++i) {
    const Vec3 at((2.0f * rng.next_1d() - 1.0f) * 4.0f, (2.0f * rng.next_1d() - 1.0f) * 4.0f, 0.3f + 2.5f * rng.next_1d());
    const float power = std::pow(10.0f, 2.0f * rng.next_1d());
    const Vec3 color(0.2f + 0.8f * rng.next_1d(), 0.2f + 0.8f * rng.next_1d(), 0.2f + 0.8f * rng.next_1d());
    lights.add_point(at, power, color, 0.0f);
    deltas.push_back({at, color * power / (4.0f * kPi)});
  }
  for (const auto& [p, n] : shading_points(5, 8)) {
    Vec3 exact(0.0f);
    for (const Delta& d : deltas) {
      const Vec3 to = d.at - p;
      const float d2 = glm::dot(to, to);
      exact += d.intensity * std::max(glm::dot(n, to) / std::sqrt(d2), 0.0f) / d2;
    }
    if (!(luminance(exact) > 0.0f)) continue;
    for (const LightSelection mode : {LightSelection::Uniform, LightSelection::Contribution}) {
      lights.set_selection(mode);
      constexpr int kDraws = 100000;
      glm::dvec3 sum(0.0);
      for (int i = 0; i < kDraws; ++i) {
        const Lights::Choice c = lights.select(p, n, (i + 0.5f) / kDraws);
        if (!(c.probability > 0.0f)) continue;
        const LightSample s = lights.sample(c.index, p, n, Vec2(0.5f));
        sum += glm::dvec3(s.weight * std::max(glm::dot(n, s.wi), 0.0f) / c.probability);
      }
      const Vec3 estimate(sum / double(kDraws));
      for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(estimate[ch], exact[ch], 2e-3f * exact[ch] + 1e-7f);
    }
  }
}

// A glossy lobe around the mirror direction of a fixed view: the BSDF-aware choice's response.
struct Lobe {
  Vec3 mirror;
  float operator()(const Vec3& wi) const {
    const float c = std::max(glm::dot(wi, mirror), 0.0f);
    return 0.1f + 50.0f * std::pow(c, 200.0f);
  }
};

TEST(LightChoice, ChoosesEachLightAsOftenAsItsProbabilitySays) {
  const Lights lights = many_lights(9, 48);
  constexpr int kDraws = 20000;
  Rng rng(0, 0, 5);
  for (const auto& [p, n] : shading_points(4, 12)) {
    const Lobe lobe{glm::normalize(n + 0.8f * uniform_sphere(rng))};
    LightChoice choice;
    choice.score(lights, p, n, false, true, lobe);
    if (!(lights.select(p, n, 0.5f).probability > 0.0f)) {  // no light reaches p: none is chosen
      EXPECT_EQ(choice.select(0.5f).probability, 0.0f);
      continue;
    }
    std::vector<int> chosen(lights.count(), 0);
    for (int i = 0; i < kDraws; ++i) {
      const Lights::Choice c = choice.select((i + 0.5f) / kDraws);
      ASSERT_LT(c.index, lights.count());
      ASSERT_GT(c.probability, 0.0f);
      EXPECT_NEAR(c.probability, choice.probability(c.index), 1e-6f * c.probability);
      ++chosen[c.index];
    }
    float total = 0.0f;
    for (size_t k = 0; k < lights.count(); ++k) {
      const float prob = choice.probability(k);
      total += prob;
      EXPECT_NEAR(chosen[k], kDraws * prob, 1.5f) << "light " << k;
      // Never below half of the irradiance choice's probability.
      EXPECT_GE(prob, 0.5f * lights.selection_probability(k, p, n) * (1.0f - 1e-4f)) << "light " << k;
    }
    EXPECT_NEAR(total, 1.0f, 1e-4f);
  }
}

// Where the lobe points at one light among 16 alike, that light gets nearly half of the choices
// or more (the irradiance choice gives it about 1/16).
TEST(LightChoice, FavoursTheLightTheLobePointsAt) {
  Lights lights;
  for (int i = 0; i < 16; ++i) lights.add_point(Vec3(std::cos(0.4f * i), std::sin(0.4f * i), 2.0f), 10.0f, Vec3(1.0f), 0.02f);
  const Vec3 p(0.0f), n(0, 0, 1);
  const Vec3 target = glm::normalize(Vec3(std::cos(0.4f * 5), std::sin(0.4f * 5), 2.0f));
  LightChoice choice;
  choice.score(lights, p, n, false, true, Lobe{target});
  EXPECT_GT(choice.probability(5), 0.4f);
  EXPECT_LT(lights.selection_probability(5, p, n), 0.1f);
  choice.score(lights, p, n, false, false, Lobe{target});  // not asked: the irradiance choice
  EXPECT_NEAR(choice.probability(5), lights.selection_probability(5, p, n), 1e-6f);
}

// LightChoice leaves its tables uninitialised (one per path): scoring without the BSDF must not
// read what a table held before. Built over memory full of NaN bytes, it gives exactly the
// irradiance choice's probabilities.
TEST(LightChoice, IrradianceChoiceReadsNothingStale) {
  const Lights lights = many_lights(3, 12);
  const Vec3 p(0.3f, -0.2f, 0.0f), n(0, 0, 1);
  alignas(LightChoice) unsigned char memory[sizeof(LightChoice)];
  std::memset(memory, 0xFF, sizeof(memory));  // every float a NaN
  LightChoice* choice = new (memory) LightChoice;
  choice->score(lights, p, n, false, false, Lobe{n});
  float total = 0.0f;
  for (size_t k = 0; k < lights.count(); ++k) {
    const float prob = choice->probability(k);
    ASSERT_TRUE(std::isfinite(prob)) << "light " << k;
    EXPECT_NEAR(prob, lights.selection_probability(k, p, n), 1e-6f) << "light " << k;
    total += prob;
  }
  EXPECT_NEAR(total, 1.0f, 1e-5f);
  choice->~LightChoice();
}

// One-light NEE through the BSDF-aware choice, weighted by the same lobe, averages to the sum
// over the lights of lobe x irradiance (delta lights: closed form).
TEST(LightChoice, NextEventEstimationIsUnbiased) {
  Lights lights;
  Rng rng(0, 0, 13);
  struct Delta {
    Vec3 at, intensity;
  };
  std::vector<Delta> deltas;
  for (int i = 0; i < 40; ++i) {
    const Vec3 at((2.0f * rng.next_1d() - 1.0f) * 4.0f, (2.0f * rng.next_1d() - 1.0f) * 4.0f, 0.3f + 2.5f * rng.next_1d());
    const float power = std::pow(10.0f, 2.0f * rng.next_1d());
    lights.add_point(at, power, Vec3(1.0f), 0.0f);
    deltas.push_back({at, Vec3(power / (4.0f * kPi))});
  }
  for (const auto& [p, n] : shading_points(6, 8)) {
    const Lobe lobe{glm::normalize(n + 0.6f * uniform_sphere(rng))};
    double exact = 0.0;
    for (const Delta& d : deltas) {
      const Vec3 to = d.at - p;
      const float d2 = glm::dot(to, to);
      const Vec3 wi = to / std::sqrt(d2);
      exact += d.intensity.x * std::max(glm::dot(n, wi), 0.0f) / d2 * lobe(wi);
    }
    if (!(exact > 0.0)) continue;
    LightChoice choice;
    choice.score(lights, p, n, false, true, lobe);
    constexpr int kDraws = 100000;
    double sum = 0.0;
    for (int i = 0; i < kDraws; ++i) {
      const Lights::Choice c = choice.select((i + 0.5f) / kDraws);
      if (!(c.probability > 0.0f)) continue;
      const LightSample s = lights.sample(c.index, p, n, Vec2(0.5f));
      sum += s.weight.x * std::max(glm::dot(n, s.wi), 0.0f) * lobe(s.wi) / c.probability;
    }
    EXPECT_NEAR(sum / kDraws, exact, 2e-3 * exact);
  }
}

// A matte floor under a sun (20 degrees wide) and a point light of radius 0.3 m, a glossy plate
// between them casting soft shadows of both: NEE of both lights at each vertex (nee_every_light,
// each of probability 1 for the MIS of BSDF-sampled hits on the lamp) renders what choosing one
// light renders (32 seeds, 16 spp), with less noise per block.
TEST(LightChoice, BothLightsRenderWhatChoosingOneRenders) {
  Scene scene;
  scene.add_material(test::diffuse_material(Vec3(0.6f)));
  Material plate;
  plate.base_color = Vec3(0.2f, 0.3f, 0.6f);
  plate.roughness = 0.3f;
  plate.specular = 0.5f;
  scene.add_material(plate);
  test::add_quad(scene, Vec3(-5, -5, 0), Vec3(5, -5, 0), Vec3(5, 5, 0), Vec3(-5, 5, 0), 0);
  test::add_quad(scene, Vec3(-0.4f, -0.4f, 0.5f), Vec3(0.4f, -0.4f, 0.5f), Vec3(0.4f, 0.4f, 0.6f),
                 Vec3(-0.4f, 0.4f, 0.6f), 1);
  scene.lights().add_sun(glm::normalize(Vec3(0.4f, 0.2f, -1.0f)), 2.0f, Vec3(1.0f, 0.95f, 0.9f), 20.0f * kPi / 180.0f);
  scene.lights().add_point(Vec3(-0.6f, 0.3f, 1.5f), 60.0f, Vec3(0.8f, 0.9f, 1.0f), 0.3f);
  test::look_down(scene, 4.0f, 20.0f);
  auto blocks = [&](bool every) {
    std::vector<std::vector<double>> out;
    RenderSettings s;
    s.width = s.height = 32;
    s.samples = 16;
    s.brdf_model = BrdfModel::Principled;
    s.nee_every_light = every;
    for (int seed = 0; seed < 32; ++seed) {
      s.seed = uint32_t(200 + seed);
      const RenderResult r = render(scene, s);
      EXPECT_EQ(r.nonfinite_samples, 0u);
      out.push_back(test::block_means_32(r.image));
    }
    return out;
  };
  // The blocks' variance over the seeds, summed.
  auto noise = [](const std::vector<std::vector<double>>& b) {
    double total = 0.0;
    for (size_t k = 0; k < b[0].size(); ++k) {
      double sum = 0.0, sum2 = 0.0;
      for (const auto& seed : b) sum += seed[k], sum2 += seed[k] * seed[k];
      const double n = double(b.size()), mean = sum / n;
      total += std::max(sum2 / n - mean * mean, 0.0);
    }
    return total;
  };
  const auto one = blocks(false), both = blocks(true);
  const test::SeedAgreement a = test::compare_over_seeds(one, both);
  std::printf("both lights against one: ratio %.4f, z %.2f, worst block z %.2f, noise %.3g vs %.3g\n", a.ratio,
              a.image_z, a.worst_block_z, noise(both), noise(one));
  test::expect_agreement(a);
  EXPECT_LT(noise(both), 0.8 * noise(one));
}

}  // namespace
}  // namespace torrance
