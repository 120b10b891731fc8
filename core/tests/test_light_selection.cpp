// Choosing one light for next-event estimation among many: the probability select() reports is
// the frequency with which it chooses, and NEE through it is unbiased.
#include "test_helpers.h"
#include "torrance/lights.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace torrance
