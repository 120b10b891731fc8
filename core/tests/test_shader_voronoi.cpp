// Blender's Voronoi Texture (core/src/shader/shader_voronoi.cpp) as Cycles 3.4 computes it: the cases of
// core/tests/data/shader_voronoi_cases.json, which Blender 3.4.1's Cycles rendered (the Python
// twin's test checks them too), the op's modes and output groups in a shader program, and
// properties over many points: F1's distance is continuous, its colour is the hash of the cell
// its position lies in, F2 is never closer than F1.
#include "json_table.h"
#include "torrance/shader/shader_hash.h"
#include "torrance/shader/shader_program.h"
#include "torrance/shader/shader_voronoi.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

namespace torrance {
namespace {

using shader::VoronoiFeature;
using shader::VoronoiInputs;
using shader::VoronoiMetric;
using shader::VoronoiOutputs;
using shader::VoronoiSettings;
using test::Json;

const char* const kFeatures[] = {"F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE", "N_SPHERE_RADIUS"};
const char* const kMetrics[] = {"EUCLIDEAN", "MANHATTAN", "CHEBYCHEV", "MINKOWSKI"};

template <size_t N>
int index_of(const char* const (&names)[N], const std::string& name) {
  for (size_t i = 0; i < N; ++i)
    if (name == names[i]) return int(i);
  throw std::runtime_error("unknown name " + name);
}

const Json& cases() { return test::json_table("shader_voronoi_cases.json"); }

// The table's rule: within 1e-6 of max(1, |expected|); "nan": NaN.
bool matches(float got, const Json& expected) {
  if (expected.kind == Json::Kind::String) return expected.text == "nan" && std::isnan(got);
  return std::fabs(got - expected.number) <= 1e-6f * std::max(1.0f, std::fabs(expected.number));
}

std::string describe(const VoronoiOutputs& o) {
  std::ostringstream s;
  s.precision(9);
  s << "distance " << o.distance << ", color (" << o.color.x << ", " << o.color.y << ", " << o.color.z
    << "), position (" << o.position.x << ", " << o.position.y << ", " << o.position.z << "), w " << o.w
    << ", radius " << o.radius;
  return s.str();
}

TEST(ShaderVoronoi, ModesPackTheSettings) {
  EXPECT_EQ(int(ShaderOpcode::Voronoi), 48);
  EXPECT_EQ(shader::kVoronoiModes, 80);
  const ShaderOpInfo info = shader_op_info(ShaderOpcode::Voronoi);
  EXPECT_EQ(info.inputs, 6);
  EXPECT_EQ(info.modes, shader::kVoronoiModes);
  EXPECT_FALSE(info.data);
  for (int mode = 0; mode < shader::kVoronoiModes; ++mode) {
    const VoronoiSettings s = shader::voronoi_settings(mode);
    EXPECT_GE(s.dimensions, 1);
    EXPECT_LE(s.dimensions, 4);
    EXPECT_EQ(shader::voronoi_mode(s), mode);
  }
  EXPECT_EQ(shader::voronoi_mode({3, VoronoiFeature::F2, VoronoiMetric::Chebychev}), 2 + 4 * 1 + 20 * 2);
}

TEST(ShaderVoronoi, CyclesCases) {
  std::set<std::tuple<int, int, int>> covered;
  const Json& rows = cases()["cases"];
  ASSERT_GE(rows.size(), 150u);
  for (const Json& row : rows.items) {
    VoronoiSettings s;
    s.dimensions = int(row[0].number);
    s.feature = VoronoiFeature(index_of(kFeatures, row[1].text));
    s.metric = VoronoiMetric(index_of(kMetrics, row[2].text));
    covered.emplace(s.dimensions, int(s.feature), int(s.metric));
    const VoronoiInputs in{row[3].vec3(), row[4].number, row[5].number, row[6].number, row[7].number, row[8].number};
    const VoronoiOutputs got = shader::voronoi(s, in);
    const float values[] = {got.distance,   got.color.x,    got.color.y, got.color.z, got.position.x,
                            got.position.y, got.position.z, got.w,       got.radius};
    const Json* expected[] = {&row[9],     &row[10][0], &row[10][1], &row[10][2], &row[11][0],
                              &row[11][1], &row[11][2], &row[12],    &row[13]};
    bool ok = true;
    for (int k = 0; k < 9; ++k) ok = ok && matches(values[k], *expected[k]);
    EXPECT_TRUE(ok) << s.dimensions << "D " << row[1].text << " " << row[2].text << " (" << row[14].text
                    << "): got " << describe(got);
  }
  // Every setting the node distinguishes: the metric in 2D to 4D for F1, F2 and Smooth F1.
  for (int d = 1; d <= 4; ++d)
    for (int f = 0; f < shader::kVoronoiFeatureCount; ++f)
      for (int m = 0; m < (d > 1 && f < 3 ? shader::kVoronoiMetricCount : 1); ++m)
        EXPECT_TRUE(covered.count({d, f, m})) << "no case for " << d << "D " << kFeatures[f] << " " << kMetrics[m];
}

// The op in a program: flags 0 (Color, Distance), 1 (Position, W), 2 (Radius, 0, 0, 0), others 0.
TEST(ShaderVoronoi, OpWritesItsOutputGroups) {
  const Vec3 vector(0.713f, -1.262f, 2.049f);
  const std::vector<glm::vec4> constants = {glm::vec4(vector, 0.0f), glm::vec4(0.9f, 0, 0, 0),
                                            glm::vec4(2.5f, 0, 0, 0), glm::vec4(0.6f, 0, 0, 0),
                                            glm::vec4(1.5f, 0, 0, 0), glm::vec4(0.8f, 0, 0, 0)};
  for (int mode = 0; mode < shader::kVoronoiModes; ++mode) {
    std::vector<ShaderInstruction> code;
    for (uint8_t flags = 0; flags < 4; ++flags) {
      ShaderInstruction ins;
      ins.op = ShaderOpcode::Voronoi;
      ins.mode = uint8_t(mode);
      ins.flags = flags;
      ins.out = int16_t(6 + flags);
      for (int k = 0; k < 6; ++k) ins.in[size_t(k)] = int16_t(k);
      code.push_back(ins);
    }
    const ShaderProgram program(constants, code, 10, 0);
    std::vector<glm::vec4> regs(10);
    program.run(ShaderGlobals{}, {}, regs.data());
    const VoronoiOutputs o = shader::voronoi(shader::voronoi_settings(mode), {vector, 0.9f, 2.5f, 0.6f, 1.5f, 0.8f});
    EXPECT_EQ(regs[6], glm::vec4(o.color, o.distance)) << "mode " << mode;
    EXPECT_EQ(regs[7], glm::vec4(o.position, o.w)) << "mode " << mode;
    EXPECT_EQ(regs[8], glm::vec4(o.radius, 0.0f, 0.0f, 0.0f)) << "mode " << mode;
    EXPECT_EQ(regs[9], glm::vec4(0.0f)) << "mode " << mode;
  }
}

VoronoiInputs random_inputs(std::mt19937& rng) {
  std::uniform_real_distribution<float> coord(-50.0f, 50.0f), unit(0.0f, 1.0f);
  return {Vec3(coord(rng), coord(rng), coord(rng)), coord(rng), 0.5f + 4.0f * unit(rng), 2.0f * unit(rng),
          0.5f + 2.0f * unit(rng), unit(rng)};
}

// F1's (and Smooth F1's) distance moves no faster than the point does (1-Lipschitz in the scaled
// coordinate for every metric but Minkowski < 1): a wrong neighbourhood would show as a jump.
TEST(ShaderVoronoi, DistanceIsContinuous) {
  std::mt19937 rng(7);
  const float step = 1e-3f;
  for (int d = 1; d <= 4; ++d)
    for (int f : {0, 2})
      for (int m = 0; m < 3; ++m) {
        const VoronoiSettings s{d, VoronoiFeature(f), VoronoiMetric(m)};
        for (int i = 0; i < 200; ++i) {
          VoronoiInputs a = random_inputs(rng);
          VoronoiInputs b = a;
          b.vector.x += step;
          b.w += step;
          const float moved = step * a.scale * (m == 1 ? 2.0f : std::sqrt(2.0f)) * 1.01f + 1e-4f;
          const float da = shader::voronoi(s, a).distance, db = shader::voronoi(s, b).distance;
          EXPECT_LE(std::fabs(da - db), moved) << d << "D " << kFeatures[f] << " " << kMetrics[m];
        }
      }
}

// F1's and F2's colours are the hash of the cell their point lies in (randomness < 1 keeps each
// point inside its cell), and F2 is never closer than F1.
TEST(ShaderVoronoi, ColorIsTheCellOfThePosition) {
  std::mt19937 rng(11);
  for (int d = 2; d <= 4; ++d)
    for (int f : {0, 1})
      for (int m = 0; m < shader::kVoronoiMetricCount; ++m) {
        const VoronoiSettings s{d, VoronoiFeature(f), VoronoiMetric(m)};
        for (int i = 0; i < 100; ++i) {
          VoronoiInputs in = random_inputs(rng);
          in.randomness = std::min(in.randomness, 0.98f);
          in.scale = 1.0f;
          const VoronoiOutputs o = shader::voronoi(s, in);
          const glm::vec4 cell = glm::floor(glm::vec4(o.position, o.w));
          const Vec3 color = d == 2   ? shader::hash_float2_to_float3(glm::vec2(cell))
                             : d == 3 ? shader::hash_float3_to_float3(Vec3(cell))
                                      : shader::hash_float4_to_float3(cell);
          EXPECT_EQ(o.color, color) << d << "D " << kFeatures[f] << " " << kMetrics[m];
          if (f == 1) {
            const VoronoiOutputs first = shader::voronoi({d, VoronoiFeature::F1, VoronoiMetric(m)}, in);
            EXPECT_GE(o.distance, first.distance);
          }
        }
      }
}

// Whatever the inputs, the program's registers stay finite (NaN and inf become 0 or +-1e30).
TEST(ShaderVoronoi, AwkwardInputsStayFinite) {
  const float awkward[] = {0.0f, -0.0f, 1e-30f, -1e30f, 1e30f, 3.0f};
  for (int mode = 0; mode < shader::kVoronoiModes; mode += 3)
    for (float a : awkward)
      for (float b : awkward) {
        const std::vector<glm::vec4> constants = {glm::vec4(a, b, a, 0.0f), glm::vec4(b, 0, 0, 0),
                                                  glm::vec4(a, 0, 0, 0), glm::vec4(b, 0, 0, 0)};
        std::vector<ShaderInstruction> code;
        for (uint8_t flags = 0; flags < 3; ++flags) {
          ShaderInstruction ins;
          ins.op = ShaderOpcode::Voronoi;
          ins.mode = uint8_t(mode);
          ins.flags = flags;
          ins.out = int16_t(4 + flags);
          ins.in = {0, 1, 2, 3, 1, 3};
          code.push_back(ins);
        }
        const ShaderProgram program(constants, code, 7, 0);
        std::vector<glm::vec4> regs(7);
        program.run(ShaderGlobals{}, {}, regs.data());
        for (int r = 4; r < 7; ++r)
          for (int k = 0; k < 4; ++k) EXPECT_TRUE(std::isfinite(regs[size_t(r)][k])) << "mode " << mode;
      }
}

}  // namespace
}  // namespace torrance
