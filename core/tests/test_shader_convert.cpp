// Blender's converter nodes (torrance::shader, shader_convert.h) as Cycles 3.4 computes them: the
// cases of data/shader_convert_cases.json (hand-computed lookups in small tables, and what Blender
// 3.4.1's Cycles renders for baked ramps and curves, Map Range, Clamp, Blackbody and Wavelength;
// the add-on's Python twin is checked against the same table), the ops as a shader program runs
// them (tables from the program's data), and no crash or NaN for degenerate tables and inputs.
#include "json_table.h"
#include "torrance/shader/shader_convert.h"
#include "torrance/shader/shader_program.h"

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

using shader::ClampMode;
using shader::MapRangeMode;

using test::Json;

const Json& table() { return test::json_table("shader_convert_cases.json"); }

MapRangeMode map_range_mode(const std::string& name) {
  if (name == "LINEAR") return MapRangeMode::Linear;
  if (name == "STEPPED") return MapRangeMode::Stepped;
  if (name == "SMOOTHSTEP") return MapRangeMode::SmoothStep;
  if (name == "SMOOTHERSTEP") return MapRangeMode::SmootherStep;
  throw std::runtime_error("no Map Range mode " + name);
}

Vec3 vec3_at(const std::vector<float>& a, size_t i) { return Vec3(a[i], a[i + 1], a[i + 2]); }

// A case's function on its arguments, flattened as the table's "about" says.
std::vector<float> evaluate(const std::string& function, const std::string& mode, const std::vector<float>& t,
                            const std::vector<float>& a) {
  const int n = int(t.size());
  if (function == "color_ramp") {
    const glm::vec4 c = shader::color_ramp(t.data(), n, a[0], a[1] != 0.0f);
    return {c.x, c.y, c.z, c.w};
  }
  if (function == "curves") {
    const Vec3 c = shader::curves(t.data(), n, a[0], vec3_at(a, 1), a[4] != 0.0f);
    return {c.x, c.y, c.z};
  }
  if (function == "float_curve") return {shader::float_curve(t.data(), n, a[0], a[1], a[2] != 0.0f)};
  if (function == "map_range")
    return {shader::map_range(map_range_mode(mode), a[0], a[1], a[2], a[3], a[4], a[5], a[6] != 0.0f)};
  if (function == "vector_map_range") {
    const Vec3 v = shader::vector_map_range(map_range_mode(mode), vec3_at(a, 0), vec3_at(a, 3), vec3_at(a, 6),
                                            vec3_at(a, 9), vec3_at(a, 12), vec3_at(a, 15), a[18] != 0.0f);
    return {v.x, v.y, v.z};
  }
  if (function == "clamp")
    return {shader::clamp(mode == "RANGE" ? ClampMode::Range : ClampMode::MinMax, a[0], a[1], a[2])};
  if (function == "blackbody") {
    const Vec3 c = shader::blackbody(a[0]);
    return {c.x, c.y, c.z};
  }
  if (function == "wavelength") {
    const Vec3 c = shader::wavelength(a[0]);
    return {c.x, c.y, c.z};
  }
  throw std::runtime_error("no function " + function);
}

TEST(ShaderConvert, CasesOfTheTable) {
  const Json& cases = table()["cases"];
  const Json& tables = table()["tables"];
  ASSERT_GT(cases.items.size(), 100u);
  std::set<std::string> functions;
  for (const Json& c : cases.items) {
    const std::string& function = c.items.at(0).text;
    const std::string& mode = c.items.at(1).text;
    const std::string& name = c.items.at(2).text;
    const std::vector<float> t = name.empty() ? std::vector<float>{} : tables[name].floats();
    const std::vector<float> args = c.items.at(3).floats(), expected = c.items.at(4).floats();
    const std::vector<float> got = evaluate(function, mode, t, args);
    functions.insert(function);
    ASSERT_EQ(got.size(), expected.size()) << function << " " << c.items.at(5).text;
    for (size_t k = 0; k < got.size(); ++k)
      EXPECT_NEAR(got[k], expected[k], 1e-5f * std::max(1.0f, std::fabs(expected[k])))
          << function << " " << mode << " " << name << " case " << c.items.at(5).text << ", component " << k;
  }
  EXPECT_EQ(functions.size(), 8u) << "a case for every function";
}

TEST(ShaderConvert, BakedTablesHaveCyclesSize) {
  const Json& tables = table()["tables"];
  EXPECT_EQ(tables["ramp_bspline_hsv"].items.size(), size_t(4 * shader::kRampTableSize));
  EXPECT_EQ(tables["rgb_curves"].items.size(), size_t(2 + 3 * shader::kRampTableSize));
  EXPECT_EQ(tables["float_curve"].items.size(), size_t(2 + shader::kRampTableSize));
}

// A program: the UV's u into each converter op (tables from the program's data), as the core runs it.
TEST(ShaderConvert, OpsRunInAProgramWithTheirTables) {
  const Json& tables = table()["tables"];
  const std::vector<float> ramp = tables["ramp_bspline_hsv"].floats();
  const std::vector<float> curve = tables["float_curve"].floats();
  std::vector<float> data;
  data.push_back(float(ramp.size()));
  data.insert(data.end(), ramp.begin(), ramp.end());
  const int curve_at = int(data.size());
  data.push_back(float(curve.size()));
  data.insert(data.end(), curve.begin(), curve.end());

  // Registers: 0 = (1, 0, 0, 0) constant, 1 = UV, 2 = u, 3 = ramp(u), 4 = float curve(1, u),
  // 5 = Map Range smoother step of u from [0.2, 0.9] to [0, 1], 6 = Blackbody(u) (800 K below).
  auto ins = [](ShaderOpcode op, int out, std::vector<int> in, int mode = 0, int flags = 0, int resource = -1) {
    ShaderInstruction i;
    i.op = op;
    i.mode = uint8_t(mode);
    i.flags = uint8_t(flags);
    i.resource = resource;
    i.out = int16_t(out);
    for (size_t k = 0; k < in.size(); ++k) i.in[k] = int16_t(in[k]);
    return i;
  };
  std::vector<glm::vec4> constants = {glm::vec4(1, 0, 0, 0), glm::vec4(0.2f, 0, 0, 0), glm::vec4(0.9f, 0, 0, 0),
                                      glm::vec4(0, 0, 0, 0)};
  std::vector<ShaderInstruction> code = {
      ins(ShaderOpcode::TexCoordUV, 4, {}),
      ins(ShaderOpcode::Channel, 5, {4}),
      ins(ShaderOpcode::ColorRamp, 6, {5}, 0, 1, 0),
      ins(ShaderOpcode::FloatCurve, 7, {0, 5}, 0, 1, curve_at),
      ins(ShaderOpcode::MapRange, 8, {5, 1, 2, 3, 0, 3}, int(MapRangeMode::SmootherStep)),
      ins(ShaderOpcode::Blackbody, 9, {5}),
  };
  const ShaderProgram program(constants, code, 10, 0, data);
  std::vector<glm::vec4> regs(10);
  for (float u : {-0.4f, 0.0f, 0.3f, 0.61f, 1.0f, 1.3f}) {
    ShaderGlobals g;
    g.uv = Vec2(u, 0.5f);
    program.run(g, {}, regs.data());
    const glm::vec4 want_ramp = shader::color_ramp(ramp.data(), int(ramp.size()), u, true);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(regs[6][k], want_ramp[k]) << u;
    EXPECT_EQ(regs[7].x, shader::float_curve(curve.data(), int(curve.size()), 1.0f, u, true)) << u;
    EXPECT_EQ(regs[8].x, shader::map_range(MapRangeMode::SmootherStep, u, 0.2f, 0.9f, 0.0f, 1.0f, 0.0f, false));
    EXPECT_EQ(Vec3(regs[9]), shader::blackbody(u));
  }
  // A table reaching past the data is rejected.
  code[3].resource = int(data.size());
  EXPECT_THROW(ShaderProgram(constants, code, 10, 0, data), std::invalid_argument);
}

TEST(ShaderConvert, OpShapes) {
  EXPECT_TRUE(shader_op_info(ShaderOpcode::ColorRamp).data);
  EXPECT_TRUE(shader_op_info(ShaderOpcode::RGBCurves).data);
  EXPECT_TRUE(shader_op_info(ShaderOpcode::VectorCurves).data);
  EXPECT_TRUE(shader_op_info(ShaderOpcode::FloatCurve).data);
  EXPECT_FALSE(shader_op_info(ShaderOpcode::MapRange).data);
  EXPECT_EQ(shader_op_info(ShaderOpcode::MapRange).modes, 4);
  EXPECT_EQ(shader_op_info(ShaderOpcode::VectorMapRange).inputs, 6);
  EXPECT_EQ(shader_op_info(ShaderOpcode::Clamp).modes, 2);
  EXPECT_EQ(int(ShaderOpcode::ColorRamp), 72);
  EXPECT_EQ(int(ShaderOpcode::Wavelength), 80);
}

// Tables too short for their shape and awkward inputs: no crash, and no NaN where Cycles has
// none (a NaN position reads the first entry).
TEST(ShaderConvert, DegenerateTablesAndInputs) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const float one[4] = {0.2f, 0.4f, 0.6f, 0.8f};
  for (int size = 0; size < 4; ++size) {
    const glm::vec4 c = shader::color_ramp(one, size, 0.5f, true);
    EXPECT_EQ(c, glm::vec4(0.0f)) << size;  // fewer than four floats: no entry
  }
  EXPECT_EQ(shader::color_ramp(one, 4, nan, true), glm::vec4(0.2f, 0.4f, 0.6f, 0.8f));
  const float curve[] = {0.0f, 1.0f, 3.0f, 5.0f};  // two values over [0, 1]
  EXPECT_EQ(shader::ramp_lookup(curve + 2, 2, 1, nan, true, true).x, 3.0f) << "NaN: the first entry";
  EXPECT_EQ(shader::float_curve(curve, 3, 1.0f, 7.0f, true), 3.0f) << "one entry: no slope to extrapolate";
  EXPECT_EQ(shader::float_curve(curve, 2, 1.0f, 0.5f, true), 0.0f) << "no entries";
  EXPECT_EQ(shader::float_curve(curve, 4, 1.0f, 2.0f, true), 7.0f);
  EXPECT_EQ(shader::float_curve(curve, 4, 0.0f, 2.0f, true), 2.0f);
  const float flat[] = {0.5f, 0.5f, 1.0f, 2.0f};  // min_x == max_x
  EXPECT_EQ(shader::float_curve(flat, 4, 1.0f, 0.5f, false), 1.0f) << "0 / 0: NaN, the first entry";
  EXPECT_EQ(shader::float_curve(flat, 4, 1.0f, 0.7f, false), 2.0f) << "+inf: the last entry";
  EXPECT_EQ(shader::curves(curve, 1, 1.0f, Vec3(0.5f), false), Vec3(0.0f));
  for (float v : {nan, inf, -inf, 0.0f, 1e30f}) {
    EXPECT_FALSE(std::isnan(shader::map_range(MapRangeMode::Linear, 0.5f, 0.0f, 1.0f, 0.0f, 1.0f, v, true)));
    EXPECT_FALSE(std::isnan(shader::clamp(ClampMode::Range, v, 0.0f, 1.0f)));
    EXPECT_FALSE(std::isnan(shader::vector_map_range(MapRangeMode::SmoothStep, Vec3(v), Vec3(0.0f), Vec3(v),
                                                     Vec3(0.0f), Vec3(1.0f), Vec3(4.0f), false)
                                .x));
    const Vec3 b = shader::blackbody(v), w = shader::wavelength(v);
    for (int k = 0; k < 3; ++k) {
      EXPECT_TRUE(std::isfinite(b[k]) && b[k] >= 0.0f) << v;
      EXPECT_TRUE(std::isfinite(w[k]) && w[k] >= 0.0f) << v;
    }
  }
}

// The fit's segments meet closely (Cycles' fit is continuous to ~1 %), and the spectrum is black
// outside 375-780 nm.
TEST(ShaderConvert, BlackbodySegmentsMeetAndWavelengthEnds) {
  for (float t : {965.0f, 1167.0f, 1449.0f, 1902.0f, 3315.0f, 6365.0f}) {
    const Vec3 below = shader::blackbody(std::nextafter(t, 0.0f)), above = shader::blackbody(t);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(below[k], above[k], 0.01f * std::max(1.0f, above[k])) << t;
  }
  EXPECT_EQ(shader::wavelength(375.0f), Vec3(0.0f));
  EXPECT_GT(shader::wavelength(375.5f).z, 0.0f);
  EXPECT_EQ(shader::wavelength(780.0f), Vec3(0.0f));
  EXPECT_GT(shader::wavelength(779.0f).x, 0.0f);
}

}  // namespace
}  // namespace torrance
