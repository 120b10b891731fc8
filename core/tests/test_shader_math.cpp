// Blender's Math and Vector Math nodes (core/src/shader/shader_math.cpp) as Cycles 3.4 computes them: the
// hand-computed cases of core/tests/data/shader_math_cases.json (which the Python twin's test
// checks too), the op names, the Clamp option, and over grids of awkward inputs no NaN or inf
// except where Cycles itself gives them.
#include "json_table.h"
#include "torrance/shader/shader_math.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace torrance {
namespace {

using shader::MathOp;
using shader::VectorMathOp;

using test::Json;

const Json& cases() { return test::json_table("shader_math_cases.json"); }

MathOp math_op_named(const std::string& name) {
  for (int i = 0; i < shader::kMathOpCount; ++i)
    if (name == shader::math_op_name(MathOp(i))) return MathOp(i);
  throw std::runtime_error("no Math op " + name);
}

VectorMathOp vector_math_op_named(const std::string& name) {
  for (int i = 0; i < shader::kVectorMathOpCount; ++i)
    if (name == shader::vector_math_op_name(VectorMathOp(i))) return VectorMathOp(i);
  throw std::runtime_error("no Vector Math op " + name);
}

// The table's rule: within 1e-6 relative (the libm functions may differ by an ulp or two between
// libraries); an expected 0 exactly (either sign).
bool matches(float got, float expected) {
  if (expected == 0.0f) return got == 0.0f;
  return std::fabs(got - expected) <= 1e-6f * std::fabs(expected);
}

std::string describe(const Vec3& v) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return s.str();
}

TEST(ShaderMath, OpsAreBlendersIdentifiersInOrder) {
  EXPECT_EQ(shader::kMathOpCount, 41);
  EXPECT_EQ(shader::kVectorMathOpCount, 27);
  EXPECT_STREQ(shader::math_op_name(MathOp::Add), "ADD");
  EXPECT_STREQ(shader::math_op_name(MathOp::MultiplyAdd), "MULTIPLY_ADD");
  EXPECT_STREQ(shader::math_op_name(MathOp::FlooredModulo), "FLOORED_MODULO");
  EXPECT_STREQ(shader::math_op_name(MathOp::PingPong), "PINGPONG");
  EXPECT_STREQ(shader::math_op_name(MathOp::Degrees), "DEGREES");
  EXPECT_STREQ(shader::math_op_name(MathOp(shader::kMathOpCount)), "");
  EXPECT_STREQ(shader::vector_math_op_name(VectorMathOp::Faceforward), "FACEFORWARD");
  EXPECT_STREQ(shader::vector_math_op_name(VectorMathOp::Fraction), "FRACTION");
  EXPECT_STREQ(shader::vector_math_op_name(VectorMathOp::Tangent), "TANGENT");
  EXPECT_STREQ(shader::vector_math_op_name(VectorMathOp(shader::kVectorMathOpCount)), "");
}

TEST(ShaderMath, HandComputedCases) {
  std::vector<bool> covered(shader::kMathOpCount, false);
  for (const Json& row : cases()["math"].items) {
    const MathOp op = math_op_named(row[0].text);
    covered[size_t(op)] = true;
    const float a = row[1].number, b = row[2].number, c = row[3].number, expected = row[4].number;
    const float got = shader::math(op, a, b, c);
    EXPECT_TRUE(matches(got, expected)) << row[0].text << "(" << a << ", " << b << ", " << c << ") = " << got
                                        << ", expected " << expected;
  }
  for (int i = 0; i < shader::kMathOpCount; ++i)
    EXPECT_TRUE(covered[size_t(i)]) << "no case for " << shader::math_op_name(MathOp(i));
}

TEST(ShaderMath, VectorHandComputedCases) {
  std::vector<bool> covered(shader::kVectorMathOpCount, false);
  for (const Json& row : cases()["vector_math"].items) {
    const VectorMathOp op = vector_math_op_named(row[0].text);
    covered[size_t(op)] = true;
    const Vec3 a = row[1].vec3(), b = row[2].vec3(), c = row[3].vec3(), expected = row[5].vec3();
    const float scale = row[4].number, expected_value = row[6].number;
    Vec3 vector(-7.0f);
    float value = -7.0f;
    shader::vector_math(op, a, b, c, scale, &vector, &value);
    const std::string call =
        row[0].text + "(" + describe(a) + ", " + describe(b) + ", " + describe(c) + ", " + std::to_string(scale) + ")";
    for (int k = 0; k < 3; ++k)
      EXPECT_TRUE(matches(vector[k], expected[k])) << call << " = " << describe(vector) << ", expected "
                                                   << describe(expected);
    EXPECT_TRUE(matches(value, expected_value)) << call << " value " << value << ", expected " << expected_value;
  }
  for (int i = 0; i < shader::kVectorMathOpCount; ++i)
    EXPECT_TRUE(covered[size_t(i)]) << "no case for " << shader::vector_math_op_name(VectorMathOp(i));
}

TEST(ShaderMath, OpsOutsideTheEnumerationGiveZero) {
  EXPECT_EQ(shader::math(MathOp(200), 1.0f, 2.0f, 3.0f), 0.0f);
  Vec3 vector(1.0f);
  float value = 1.0f;
  shader::vector_math(VectorMathOp(200), Vec3(1.0f), Vec3(2.0f), Vec3(3.0f), 4.0f, &vector, &value);
  EXPECT_EQ(vector, Vec3(0.0f));
  EXPECT_EQ(value, 0.0f);
  shader::vector_math(VectorMathOp::Length, Vec3(3.0f, 4.0f, 0.0f), Vec3(0.0f), Vec3(0.0f), 0.0f, nullptr, &value);
  EXPECT_EQ(value, 5.0f) << "either output may be skipped";
}

TEST(ShaderMath, ClampOptionIsCyclesClampNode) {
  EXPECT_EQ(shader::clamp_unit(-0.5f), 0.0f);
  EXPECT_EQ(shader::clamp_unit(0.25f), 0.25f);
  EXPECT_EQ(shader::clamp_unit(3.0f), 1.0f);
  EXPECT_EQ(shader::clamp_unit(INFINITY), 1.0f);
  EXPECT_EQ(shader::clamp_unit(NAN), 0.0f) << "Cycles' clamp is max then min by comparisons: NaN -> 0";
  EXPECT_EQ(shader::clamp_unit(shader::math(MathOp::Subtract, 1.0f, 3.0f, 0.0f)), 0.0f);
}

// The Math ops whose result overflows to inf for some finite inputs in Cycles too (no guard there):
// products and quotients, exp/sinh/cosh, and the ops that divide by a tiny divisor and multiply
// the floored ratio back (floored modulo, wrap, snap; 1e30 / 1e-30 is inf in float).
bool may_overflow(MathOp op) {
  switch (op) {
    case MathOp::Multiply:
    case MathOp::Divide:
    case MathOp::MultiplyAdd:
    case MathOp::Power:
    case MathOp::Exponent:
    case MathOp::Sinh:
    case MathOp::Cosh:
    case MathOp::FlooredModulo:
    case MathOp::Wrap:
    case MathOp::Snap: return true;
    default: return false;
  }
}

TEST(ShaderMath, NoNaNOverAwkwardInputs) {
  const float grid[] = {0.0f, -0.0f, 1e-30f, -1e-30f, 1.0f, -1.0f, 1e30f, -1e30f};
  for (int i = 0; i < shader::kMathOpCount; ++i) {
    const MathOp op = MathOp(i);
    for (float a : grid)
      for (float b : grid)
        for (float c : grid) {
          const float r = shader::math(op, a, b, c);
          const auto where = [&] {
            std::ostringstream s;
            s << shader::math_op_name(op) << "(" << a << ", " << b << ", " << c << ") = " << r;
            return s.str();
          };
          if (std::isnan(r)) {
            // Cycles' one NaN for finite inputs: Ping-Pong's fract(inf) when a is huge against b.
            EXPECT_TRUE(op == MathOp::PingPong && !std::isfinite((a - b) / (b * 2.0f))) << where();
          } else if (std::isinf(r)) {
            EXPECT_TRUE(may_overflow(op)) << where();
          }
        }
  }
}

// Without the huge inputs every result is finite, the guards' included, but for Power where the
// power itself exceeds float (0 to a negative power is +inf in Cycles' CPU kernels).
TEST(ShaderMath, FiniteOverModerateInputs) {
  const float grid[] = {0.0f, -0.0f, 1e-30f, -1e-30f, 0.5f, -0.5f, 1.0f, -1.0f, 3.0f, -3.0f};
  for (int i = 0; i < shader::kMathOpCount; ++i) {
    const MathOp op = MathOp(i);
    for (float a : grid)
      for (float b : grid)
        for (float c : grid) {
          const float r = shader::math(op, a, b, c);
          if (op == MathOp::Power && std::fabs(std::pow(double(a), double(b))) > FLT_MAX) continue;
          EXPECT_TRUE(std::isfinite(r)) << shader::math_op_name(op) << "(" << a << ", " << b << ", " << c
                                        << ") = " << r;
        }
  }
}

// Vectors with components from {0, +-1e-30, +-1}: every output finite but Reflect's and Refract's
// for a normal whose squared length is 0 in float (Cycles 3.4 normalises it unguarded: 0 / 0).
TEST(ShaderMath, VectorFiniteOverModerateInputs) {
  const float components[] = {0.0f, 1e-30f, -1e-30f, 1.0f, -1.0f};
  std::vector<Vec3> vectors;
  for (float x : components)
    for (float y : components)
      for (float z : components) vectors.emplace_back(x, y, z);
  const Vec3 thirds[] = {Vec3(0.0f), Vec3(1.0f, -1e-30f, 0.5f), Vec3(-1.0f, 1.0f, 1e-30f)};
  const float scales[] = {0.0f, 1e-30f, -1.0f, 1.5f};
  int failures = 0;
  for (int i = 0; i < shader::kVectorMathOpCount && failures < 10; ++i) {
    const VectorMathOp op = VectorMathOp(i);
    for (const Vec3& a : vectors)
      for (const Vec3& b : vectors)
        for (const Vec3& c : thirds)
          for (float s : scales) {
            Vec3 vector;
            float value;
            shader::vector_math(op, a, b, c, s, &vector, &value);
            const bool zero_normal = b.x * b.x + b.y * b.y + b.z * b.z == 0.0f;
            if ((op == VectorMathOp::Reflect || op == VectorMathOp::Refract) && zero_normal) continue;
            if (!is_finite(vector) || !std::isfinite(value)) {
              ADD_FAILURE() << shader::vector_math_op_name(op) << "(" << describe(a) << ", " << describe(b) << ", "
                            << describe(c) << ", " << s << ") = " << describe(vector) << ", " << value;
              ++failures;
            }
          }
  }
}

// Cycles 3.4 normalises Reflect's and Refract's normal unguarded; the program running the ops
// keeps its registers finite.
TEST(ShaderMath, ZeroNormalIsNaNAsInCycles34) {
  Vec3 vector;
  float value;
  shader::vector_math(VectorMathOp::Reflect, Vec3(1, 2, 3), Vec3(0.0f), Vec3(0.0f), 0.0f, &vector, &value);
  EXPECT_TRUE(std::isnan(vector.x) && std::isnan(vector.y) && std::isnan(vector.z)) << describe(vector);
  shader::vector_math(VectorMathOp::Refract, Vec3(1, 2, 3), Vec3(1e-30f, 0, 0), Vec3(0.0f), 1.5f, &vector, &value);
  EXPECT_TRUE(std::isnan(vector.x) && std::isnan(vector.y) && std::isnan(vector.z)) << describe(vector);
}

}  // namespace
}  // namespace torrance
