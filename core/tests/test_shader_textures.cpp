// Blender's Checker, Gradient, Brick and Magic Texture nodes (core/src/shader/shader_textures.cpp) as
// Cycles 3.4 computes them: the cases of core/tests/data/shader_textures_cases.json, which Blender
// 3.4.1's Cycles rendered (the Python twin's test checks them too), each also run as a shader
// program (the ops' inputs, modes and flags), and the values' edges: the integer noise's wrap,
// huge and degenerate inputs.
#include "torrance/shader/shader_program.h"
#include "torrance/shader/shader_textures.h"

#include "json_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace torrance {
namespace {

using shader::GradientType;
using test::Json;

const Json& cases() { return test::json_table("shader_textures_cases.json"); }

// The table's rule: within 1e-6, relative beyond 1 (Cycles' kernels round an ulp or two apart).
bool matches(float got, float expected) {
  return std::fabs(got - expected) <= 1e-6f * std::fmax(1.0f, std::fabs(expected));
}
bool matches(const Vec3& got, const Vec3& expected) {
  return matches(got.x, expected.x) && matches(got.y, expected.y) && matches(got.z, expected.z);
}

std::string describe(const Vec3& v) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

GradientType gradient_named(const std::string& name) {
  const char* names[] = {"LINEAR", "QUADRATIC", "EASING", "DIAGONAL", "SPHERICAL", "QUADRATIC_SPHERE", "RADIAL"};
  for (int i = 0; i < shader::kGradientTypeCount; ++i)
    if (name == names[i]) return GradientType(i);
  throw std::runtime_error("no gradient type " + name);
}

shader::BrickRows brick_rows(const Json& settings) {
  return {settings[0].number, int(settings[1].number), settings[2].number, int(settings[3].number)};
}

// A one-instruction program over constant registers: the op's Color (flags 0) and Fac (flags 1).
struct OpResult {
  glm::vec4 color, fac;
};
OpResult run_op(ShaderOpcode op, int mode, const std::vector<glm::vec4>& inputs) {
  std::vector<ShaderInstruction> code(2);
  for (int k = 0; k < 2; ++k) {
    ShaderInstruction& ins = code[size_t(k)];
    ins.op = op;
    ins.mode = uint8_t(mode);
    ins.flags = uint8_t(k);
    ins.out = int16_t(inputs.size() + size_t(k));
    for (size_t i = 0; i < inputs.size(); ++i) ins.in[i] = int16_t(i);
  }
  const ShaderProgram program(inputs, code, int(inputs.size()) + 2, 0);
  std::vector<glm::vec4> regs(size_t(program.registers()));
  program.run(ShaderGlobals{}, {}, regs.data());
  return {regs[inputs.size()], regs[inputs.size() + 1]};
}

glm::vec4 reg(const Vec3& v) { return glm::vec4(v, 0.0f); }
glm::vec4 reg(float v) { return glm::vec4(v, 0.0f, 0.0f, 0.0f); }

void expect_op(const OpResult& r, const Vec3& color, float fac, const std::string& what) {
  EXPECT_TRUE(matches(Vec3(r.color), color) && r.color.w == 1.0f)
      << what << ": the op's Color " << describe(Vec3(r.color)) << " w " << r.color.w << ", expected "
      << describe(color);
  EXPECT_TRUE(matches(r.fac.x, fac) && r.fac.y == 0.0f && r.fac.z == 0.0f && r.fac.w == 0.0f)
      << what << ": the op's Fac " << r.fac.x << ", expected " << fac;
}

TEST(ShaderTextures, OpShapes) {
  EXPECT_EQ(int(ShaderOpcode::TexChecker), 56);
  EXPECT_EQ(int(ShaderOpcode::TexMagic), 59);
  EXPECT_EQ(shader_op_info(ShaderOpcode::TexChecker).inputs, 4);
  EXPECT_EQ(shader_op_info(ShaderOpcode::TexGradient).modes, 7);
  EXPECT_EQ(shader_op_info(ShaderOpcode::TexBrick).inputs, 11);
  EXPECT_EQ(shader_op_info(ShaderOpcode::TexMagic).modes, 11);
  for (int op = 56; op < 60; ++op) EXPECT_NE(shader_op_info(ShaderOpcode(op)).run, nullptr) << op;
}

TEST(ShaderTextures, CheckerAsCycles) {
  ASSERT_GT(cases()["checker"].size(), 10u);
  for (const Json& row : cases()["checker"].items) {
    const Vec3 v = row[0].vec3(), c1 = row[1].vec3(), c2 = row[2].vec3(), color = row[4].vec3();
    const float scale = row[3].number, fac = row[5].number;
    const float f = shader::checker(v * scale);
    const std::string what = "checker at " + describe(v) + " * " + std::to_string(scale);
    EXPECT_EQ(f, fac) << what;
    EXPECT_EQ(f == 1.0f ? c1 : c2, color) << what;
    expect_op(run_op(ShaderOpcode::TexChecker, 0, {reg(v), reg(c1), reg(c2), reg(scale)}), color, fac, what);
  }
}

TEST(ShaderTextures, GradientAsCycles) {
  std::vector<bool> covered(shader::kGradientTypeCount, false);
  for (const Json& row : cases()["gradient"].items) {
    const GradientType type = gradient_named(row[0].text);
    covered[size_t(type)] = true;
    const Vec3 v = row[1].vec3();
    const float fac = row[2].number;
    const float f = shader::gradient(type, v);
    const std::string what = row[0].text + " gradient at " + describe(v);
    EXPECT_TRUE(matches(f, fac)) << what << " = " << f << ", expected " << fac;
    expect_op(run_op(ShaderOpcode::TexGradient, int(type), {reg(v)}), Vec3(fac), fac, what);
  }
  for (int i = 0; i < shader::kGradientTypeCount; ++i) EXPECT_TRUE(covered[size_t(i)]) << "no case for type " << i;
  EXPECT_EQ(shader::gradient(GradientType(200), Vec3(0.5f)), 0.0f);
}

TEST(ShaderTextures, BrickAsCycles) {
  ASSERT_GT(cases()["brick"].size(), 60u);
  int mortar = 0, brick = 0, between = 0;
  for (const Json& row : cases()["brick"].items) {
    const Vec3 v = row[0].vec3(), c1 = row[1].vec3(), c2 = row[2].vec3(), cm = row[3].vec3();
    const float scale = row[4].number, size = row[5].number, smooth = row[6].number, bias = row[7].number;
    const float width = row[8].number, height = row[9].number;
    const Json& settings = row[10];
    const Vec3 color = row[11].vec3();
    const float fac = row[12].number;
    const shader::BrickSample s = shader::brick(v * scale, size, smooth, bias, width, height, brick_rows(settings));
    const Vec3 got = shader::brick_color(s, c1, c2, cm);
    const std::string what = "brick at " + describe(v) + " * " + std::to_string(scale);
    EXPECT_TRUE(matches(s.mortar, fac)) << what << ": Fac " << s.mortar << ", expected " << fac;
    EXPECT_TRUE(matches(got, color)) << what << ": Color " << describe(got) << ", expected " << describe(color);
    const glm::vec4 rows(settings[0].number, settings[1].number, settings[2].number, settings[3].number);
    expect_op(run_op(ShaderOpcode::TexBrick, 0,
                     {reg(v), reg(c1), reg(c2), reg(cm), reg(scale), reg(size), reg(smooth), reg(bias), reg(width),
                      reg(height), rows}),
              color, fac, what);
    (fac == 1.0f ? mortar : fac == 0.0f ? brick : between) += 1;
  }
  EXPECT_GT(mortar, 3);
  EXPECT_GT(brick, 30);
  EXPECT_GT(between, 5) << "cases in the mortar's smooth band";
}

TEST(ShaderTextures, MagicAsCycles) {
  std::vector<bool> covered(shader::kMagicDepths, false);
  for (const Json& row : cases()["magic"].items) {
    const int depth = int(row[0].number);
    covered[size_t(depth)] = true;
    const Vec3 v = row[1].vec3(), color = row[4].vec3();
    const float scale = row[2].number, distortion = row[3].number, fac = row[5].number;
    const Vec3 got = shader::magic(v, scale, depth, distortion);
    const std::string what = "magic depth " + std::to_string(depth) + " at " + describe(v) + ", scale " +
                             std::to_string(scale) + ", distortion " + std::to_string(distortion);
    EXPECT_TRUE(matches(got, color)) << what << ": " << describe(got) << ", expected " << describe(color);
    expect_op(run_op(ShaderOpcode::TexMagic, depth, {reg(v), reg(scale), reg(distortion)}), color, fac, what);
  }
  for (int d = 0; d < shader::kMagicDepths; ++d) EXPECT_TRUE(covered[size_t(d)]) << "no case for depth " << d;
  const Vec3 p(0.3f, -0.2f, 0.7f);
  EXPECT_EQ(shader::magic(p, 1.5f, 14, 1.2f), shader::magic(p, 1.5f, 10, 1.2f)) << "depths beyond 10 are 10";
  EXPECT_EQ(shader::magic(p, 1.5f, -3, 1.2f), shader::magic(p, 1.5f, 0, 1.2f));
}

TEST(ShaderTextures, BrickNoiseWrapsAt32Bits) {
  for (const Json& row : cases()["brick_noise"].items) {
    const uint32_t n = uint32_t(row[0].exact);
    EXPECT_EQ(shader::brick_noise(n), row[1].number) << n;
  }
  EXPECT_EQ(shader::brick_noise(0u), shader::brick_noise(0x80000000u)) << "the top bit is masked";
}

// Rows and bricks at negative coordinates: the offset rows are 0, -2, -4, ..., and the tint comes
// from the row's and column's two's complement bits.
TEST(ShaderTextures, BrickRowsBelowZero) {
  const shader::BrickRows rows{0.5f, 2, 1.0f, 2};
  // Row -2 (offset by half a brick: x 0.1 + 0.25 stays in column 0) and row -1 (not offset).
  const shader::BrickSample a = shader::brick(Vec3(0.1f, -0.4f, 0.0f), 0.0f, 0.0f, 0.0f, 0.5f, 0.25f, rows);
  const shader::BrickSample b = shader::brick(Vec3(0.1f, -0.2f, 0.0f), 0.0f, 0.0f, 0.0f, 0.5f, 0.25f, rows);
  EXPECT_EQ(a.tint, shader::brick_noise((uint32_t(-2) << 16) + 0u));
  EXPECT_EQ(b.tint, shader::brick_noise((uint32_t(-1) << 16) + 0u));
  const shader::BrickSample c = shader::brick(Vec3(-0.1f, -0.2f, 0.0f), 0.0f, 0.0f, 0.0f, 0.5f, 0.25f, rows);
  EXPECT_EQ(c.tint, shader::brick_noise((uint32_t(-1) << 16) + 0xffffu)) << "column -1";
}

// Degenerate settings (zero widths, frequencies, mortar) and huge coordinates: x86's conversions
// (INT_MIN), no traps; every value a program keeps is finite.
TEST(ShaderTextures, DegenerateAndHugeInputs) {
  const float values[] = {0.0f, -0.0f, 1e-30f, -1e-30f, 0.5f, -2.0f, 1e30f, -1e30f};
  int runs = 0;
  for (float a : values)
    for (float b : values) {
      const Vec3 p(a, b, 0.25f);
      for (int f = -1; f < 3; ++f) {
        const shader::BrickSample s = shader::brick(p, a, b, 0.0f, b, a, {0.5f, f, 2.0f, f + 1});
        EXPECT_FALSE(std::isnan(s.tint)) << describe(p);
        EXPECT_GE(s.tint, 0.0f);
        EXPECT_LE(s.tint, 1.0f);
      }
      EXPECT_TRUE(shader::checker(p) == 0.0f || shader::checker(p) == 1.0f);
      for (int t = 0; t < shader::kGradientTypeCount; ++t) {
        const float g = shader::gradient(GradientType(t), p);
        EXPECT_TRUE(g >= 0.0f && g <= 1.0f) << t << " at " << describe(p) << " = " << g;
      }
      const std::vector<glm::vec4> brick_inputs = {reg(p),    reg(Vec3(1.0f)), reg(Vec3(0.0f)), reg(Vec3(0.5f)),
                                                   reg(a),    reg(b),          reg(a),          reg(b),
                                                   reg(a),    reg(b),          glm::vec4(a, b, a, -b)};
      const OpResult r = run_op(ShaderOpcode::TexBrick, 0, brick_inputs);
      const OpResult m = run_op(ShaderOpcode::TexMagic, 10, {reg(p), reg(a), reg(b)});
      for (const glm::vec4& v : {r.color, r.fac, m.color, m.fac})
        EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w));
      ++runs;
    }
  EXPECT_EQ(runs, 64);
  // Moderate inputs give finite Magic colours (huge ones may not: sin(inf) is NaN in Cycles too).
  for (float scale : {0.0f, 1.0f, -7.0f})
    for (float distortion : {0.0f, 1e-30f, 2.0f, -40.0f})
      for (int depth = 0; depth < shader::kMagicDepths; ++depth)
        EXPECT_TRUE(is_finite(shader::magic(Vec3(1e6f, -3.0f, 0.5f), scale, depth, distortion)));
}

}  // namespace
}  // namespace torrance
