// The colour ops of Blender's shader nodes (torrance::shader, shader_color.h) as Cycles 3.4
// computes them: the hand-computed cases the add-on's Python twin is checked against too
// (data/shader_color_cases.json, checked once against Blender 3.4's Cycles), colour-model round
// trips, and finite results for awkward inputs.
#include "json_table.h"
#include "torrance/shader/shader_color.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace torrance {
namespace {

using shader::MixBlend;

using test::Json;

// A case's arguments or expected values as floats, in order (the strings inf/-inf/nan as numbers).
void flatten(const Json& v, std::vector<float>& out) {
  if (v.kind == Json::Kind::Array) {
    for (const Json& item : v.items) flatten(item, out);
  } else if (v.kind == Json::Kind::String) {
    const float inf = std::numeric_limits<float>::infinity();
    out.push_back(v.text == "inf" ? inf : v.text == "-inf" ? -inf : std::nanf(""));
  } else {
    out.push_back(float(v.exact));  // strtod, then float (true/false: 1, 0)
  }
}

const Json& read_cases() { return test::json_table("shader_color_cases.json"); }

// MixBlend's identifiers, as Blender names them.
const char* const kBlendNames[] = {"MIX", "DARKEN", "MULTIPLY", "BURN", "LIGHTEN", "SCREEN", "DODGE",
                                   "ADD", "OVERLAY", "SOFT_LIGHT", "LINEAR_LIGHT", "DIFFERENCE",
                                   "EXCLUSION", "SUBTRACT", "DIVIDE", "HUE", "SATURATION", "COLOR",
                                   "VALUE"};
static_assert(sizeof(kBlendNames) / sizeof(kBlendNames[0]) == shader::kMixBlendCount);

MixBlend blend_named(const std::string& name) {
  for (int i = 0; i < shader::kMixBlendCount; ++i)
    if (name == kBlendNames[i]) return MixBlend(i);
  throw std::runtime_error("no blend " + name);
}

Vec3 vec(const std::vector<float>& a, size_t at) { return Vec3(a.at(at), a.at(at + 1), a.at(at + 2)); }
std::vector<float> list(const Vec3& v) { return {v.x, v.y, v.z}; }

std::vector<float> evaluate(const std::string& f, const std::string& blend, const std::vector<float>& a) {
  if (f == "mix_color") return list(shader::mix_color(blend_named(blend), a[0], vec(a, 1), vec(a, 4), a.at(7) != 0.0f));
  if (f == "mix_factor") return {shader::mix_factor(a[0], a.at(1) != 0.0f)};
  if (f == "mix_float") return {shader::mix_float(a[0], a[1], a.at(2))};
  if (f == "mix_vector") return list(shader::mix_vector(vec(a, 0), vec(a, 3), vec(a, 6)));
  if (f == "rgb_to_hsv") return list(shader::rgb_to_hsv(vec(a, 0)));
  if (f == "hsv_to_rgb") return list(shader::hsv_to_rgb(vec(a, 0)));
  if (f == "rgb_to_hsl") return list(shader::rgb_to_hsl(vec(a, 0)));
  if (f == "hsl_to_rgb") return list(shader::hsl_to_rgb(vec(a, 0)));
  if (f == "hue_saturation_value") return list(shader::hue_saturation_value(a[0], a[1], a[2], a[3], vec(a, 4)));
  if (f == "invert") return list(shader::invert(a[0], vec(a, 1)));
  if (f == "gamma") return list(shader::gamma(vec(a, 0), a.at(3)));
  if (f == "bright_contrast") return list(shader::bright_contrast(vec(a, 0), a[3], a.at(4)));
  if (f == "rgb_to_bw") return {shader::rgb_to_bw(vec(a, 0))};
  throw std::runtime_error("no function " + f);
}

bool agrees(float got, float expected) {
  if (std::isnan(expected)) return std::isnan(got);
  if (std::isinf(expected)) return got == expected;
  return std::fabs(got - expected) <= 1e-5f * std::max(1.0f, std::fabs(expected));
}

TEST(ShaderColor, HandComputedCasesAgree) {
  const Json cases = read_cases()["cases"];
  ASSERT_GT(cases.items.size(), 90u);
  for (const Json& c : cases.items) {
    const std::string& function = c.items.at(0).text;
    const std::string& blend = c.items.at(1).text;
    std::vector<float> args, expected;
    flatten(c.items.at(2), args);
    flatten(c.items.at(3), expected);
    const std::vector<float> got = evaluate(function, blend, args);
    ASSERT_EQ(got.size(), expected.size()) << function;
    for (size_t i = 0; i < got.size(); ++i)
      EXPECT_TRUE(agrees(got[i], expected[i]))
          << function << " " << blend << " (" << c.items.at(4).text << ") component " << i
          << ": " << got[i] << ", expected " << expected[i];
  }
}

TEST(ShaderColor, EveryBlendHasACase) {
  const Json cases = read_cases()["cases"];
  std::set<std::string> covered;
  for (const Json& c : cases.items)
    if (c.items.at(0).text == "mix_color") covered.insert(c.items.at(1).text);
  EXPECT_EQ(covered.size(), size_t(shader::kMixBlendCount));
  EXPECT_EQ(int(MixBlend::EXCLUSION), 12);
  EXPECT_EQ(int(MixBlend::VALUE), shader::kMixBlendCount - 1);
}

const float kGrid[] = {0.0f, 0.1f, 0.25f, 0.5f, 0.7f, 1.0f};

bool close(const Vec3& a, const Vec3& b, float tolerance) {
  for (int i = 0; i < 3; ++i)
    if (!(std::fabs(a[i] - b[i]) <= tolerance * std::max(1.0f, std::fabs(b[i])))) return false;
  return true;
}

TEST(ShaderColor, HsvRoundTrip) {
  // Exact, to rounding, for every colour whose maximum is not 0: [0, 1], HDR, negative channels.
  std::vector<Vec3> colours = {{2, 1, 0}, {5, 0.5f, 3}, {-0.5f, -0.2f, -0.1f}, {1, -0.5f, 0.2f},
                               {-2, 0.3f, 0.1f}, {-1, -1, -3}};
  for (float r : kGrid)
    for (float g : kGrid)
      for (float b : kGrid) colours.emplace_back(r, g, b);
  for (const Vec3& c : colours) {
    const Vec3 back = shader::hsv_to_rgb(shader::rgb_to_hsv(c));
    EXPECT_TRUE(close(back, c, 2e-6f)) << c.x << " " << c.y << " " << c.z << " -> " << back.x
                                       << " " << back.y << " " << back.z;
  }
  EXPECT_EQ(shader::hsv_to_rgb(shader::rgb_to_hsv(Vec3(0, -1, -0.5f))), Vec3(0.0f));
}

TEST(ShaderColor, HslRoundTrip) {
  // Exact within [0, 1]; above, the lightness is clamped to 1.
  for (float r : kGrid)
    for (float g : kGrid)
      for (float b : kGrid) {
        const Vec3 c(r, g, b), back = shader::hsl_to_rgb(shader::rgb_to_hsl(c));
        EXPECT_TRUE(close(back, c, 2e-6f)) << r << " " << g << " " << b;
      }
  EXPECT_EQ(shader::hsl_to_rgb(shader::rgb_to_hsl(Vec3(2.0f))), Vec3(1.0f));
}

TEST(ShaderColor, AwkwardInputsGiveFiniteResults) {
  const float values[] = {0.0f, -0.0f, -1.0f, -0.3f, 0.5f, 1.0f, 1.7f, 40.0f};
  const float factors[] = {-1.0f, -0.2f, 0.0f, 0.5f, 1.0f, 1.3f, 3.0f};
  std::vector<Vec3> colours;
  for (float r : values)
    for (float g : values)
      for (float b : values) colours.emplace_back(r, g, b);
  int singular_hsl = 0;
  for (size_t i = 0; i < colours.size(); i += 7) {
    const Vec3 a = colours[i], b = colours[colours.size() - 1 - i];
    for (float fac : factors)
      for (bool clamp : {false, true}) {
        for (int blend = 0; blend < shader::kMixBlendCount; ++blend) {
          const Vec3 r = shader::mix_color(MixBlend(blend), shader::mix_factor(fac, clamp), a, b, clamp);
          ASSERT_TRUE(is_finite(r)) << kBlendNames[blend] << " fac " << fac;
          if (clamp) {
            EXPECT_TRUE(r == glm::clamp(r, 0.0f, 1.0f)) << kBlendNames[blend];
          }
        }
        EXPECT_TRUE(std::isfinite(shader::mix_float(fac, a.x, b.x)));
        EXPECT_TRUE(is_finite(shader::mix_vector(Vec3(fac, 1.0f - fac, 2.0f * fac), a, b)));
        EXPECT_TRUE(is_finite(shader::hue_saturation_value(fac, b.x, b.y, fac, a)));
        EXPECT_TRUE(is_finite(shader::invert(fac, a)));
        EXPECT_TRUE(is_finite(shader::bright_contrast(a, fac, b.z)));
      }
    for (float g : {0.0f, -2.0f, 0.5f, 3.0f}) EXPECT_TRUE(is_finite(shader::gamma(a, g)));
    EXPECT_TRUE(is_finite(shader::rgb_to_hsv(a)));
    EXPECT_TRUE(is_finite(shader::hsv_to_rgb(a)));
    EXPECT_TRUE(is_finite(shader::hsl_to_rgb(a)));
    EXPECT_TRUE(std::isfinite(shader::rgb_to_bw(a)));
    // rgb_to_hsl divides by 2 - max - min (lightness > 0.5) or max + min unguarded, as Cycles.
    const float top = max_component(a), bottom = std::min(a.x, std::min(a.y, a.z));
    const float lightness = std::min(1.0f, (top + bottom) / 2.0f);
    const bool singular = top != bottom && (lightness > 0.5f ? 2.0f - top - bottom : top + bottom) == 0.0f;
    singular_hsl += singular;
    EXPECT_NE(is_finite(shader::rgb_to_hsl(a)), singular) << a.x << " " << a.y << " " << a.z;
  }
  EXPECT_GT(singular_hsl, 0);
}

}  // namespace
}  // namespace torrance
