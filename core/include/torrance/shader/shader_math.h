// Blender's Math and Vector Math shader nodes (ShaderNodeMath, ShaderNodeVectorMath), operation by
// operation as Cycles 3.4 evaluates them on the CPU, in float32 and with Cycles' guards: a divisor
// of 0 gives 0, a logarithm of a non-positive number 0, the square root of a negative number 0, a
// negative base to a non-integer power 0, and so on (each op's comment below says what it does).
// Where Cycles has no guard the result is Cycles' too: Power of 0 to a negative exponent is +inf,
// products overflow to inf, Ping-Pong of a value huge against its scale is NaN (the fraction of
// an infinite ratio), and Reflect and Refract with a zero normal are NaN (3.4 normalises the
// normal unguarded). The program that runs these ops keeps its values finite.
//
// The Python twin (python_addon/torrance/shader_graph/math_ops.py) is the add-on's constant folder;
// both are checked against the same table, core/tests/data/shader_math_cases.json.
#pragma once

#include "torrance/util/math.h"

#include <cstdint>

namespace torrance::shader {

// The Math node's operations, one per Blender identifier, in this order (the add-on's MATH_OPS).
enum class MathOp : uint8_t {
  Add,            // a + b
  Subtract,       // a - b
  Multiply,       // a * b
  Divide,         // a / b; 0 if b == 0
  MultiplyAdd,    // a * b + c
  Power,          // a^b; 0 if a < 0 and b is not an integer (3e9 is one); pow(0, -1) = +inf
  Logarithm,      // log(a) / log(b); 0 if a <= 0 or b <= 0, or b == 1
  Sqrt,           // sqrt(max(a, 0))
  InverseSqrt,    // 1 / sqrt(a); 0 if a <= 0
  Absolute,       // |a|
  Exponent,       // e^a
  Minimum,        // fmin(a, b)
  Maximum,        // fmax(a, b)
  LessThan,       // a < b ? 1 : 0
  GreaterThan,    // a > b ? 1 : 0
  Sign,           // -1, 0 or 1 (0 for -0 too)
  Compare,        // 1 if a == b or |a - b| <= max(c, FLT_EPSILON), else 0
  SmoothMin,      // min(a, b) - h^3 k / 6, h = max(k - |a - b|, 0) / k, k = c; min(a, b) if c == 0
  SmoothMax,      // -SmoothMin(-a, -b, c)
  Round,          // floor(a + 0.5), the sum in float (so 0.49999997 rounds to 1)
  Floor,          // floor(a)
  Ceil,           // ceil(a)
  Trunc,          // a >= 0 ? floor(a) : ceil(a)
  Fract,          // a - floor(a)
  Modulo,         // fmod(a, b) (truncated: the sign of a); 0 if b == 0
  FlooredModulo,  // a - floor(a / b) * b (the sign of b; Blender 4.x); 0 if b == 0
  Wrap,           // a wrapped into [c, b): a - r floor((a - c) / r), r = b - c; c if r == 0
  Snap,           // floor(a / b) * b; 0 if b == 0
  PingPong,       // |fract((a - b) / 2b) 2b - b| (a bounced between 0 and b); 0 if b == 0
  Sine,           // sin(a)
  Cosine,         // cos(a)
  Tangent,        // tan(a)
  Arcsine,        // asin(a clamped to [-1, 1])
  Arccosine,      // acos(a clamped to [-1, 1])
  Arctangent,     // atan(a)
  Arctan2,        // atan2(a, b)
  Sinh,           // sinh(a)
  Cosh,           // cosh(a)
  Tanh,           // tanh(a)
  Radians,        // a * (pi / 180)
  Degrees,        // a * (180 / pi)
};
constexpr int kMathOpCount = int(MathOp::Degrees) + 1;

// The Math node's operation on its three inputs (a, b, c: the node's inputs from the top). An op
// outside the enumeration gives 0, as in Cycles.
float math(MathOp op, float a, float b, float c);

// The Math node's Clamp option: the result clamped to [0, 1] as Cycles' Clamp node does it, which
// also turns NaN into 0 (std::clamp would keep it).
float clamp_unit(float v);

// The Vector Math node's operations, one per Blender identifier, in this order (VECTOR_MATH_OPS).
// Inputs: a, b, c = Vector, Vector_001, Vector_002; s = Scale. Operations on components apply
// the Math node's op of that name to each.
enum class VectorMathOp : uint8_t {
  Add,           // a + b
  Subtract,      // a - b
  Multiply,      // a * b
  Divide,        // a / b; a component of 0 where b's is 0
  MultiplyAdd,   // a * b + c
  CrossProduct,  // a x b
  Project,       // (a.b / b.b) b; 0 if b.b == 0 (in float, |b| below ~3e-23 too)
  Reflect,       // a - 2 n (a.n), n = b / |b| (NaN if b.b is 0 in float: 3.4 does not guard)
  Refract,       // refract(a, b / |b|, eta = s): 0 on total internal reflection; NaN if |b| is 0
  Faceforward,   // c.b < 0 ? a : -a
  DotProduct,    // value: a.b
  Distance,      // value: |a - b|
  Length,        // value: |a|
  Scale,         // a * s
  Normalize,     // a / |a|; a itself if |a| is 0 in float
  Absolute,      // |a| per component
  Minimum,       // per component, a < b ? a : b
  Maximum,       // per component, a > b ? a : b
  Floor,         // per component
  Ceil,          // per component
  Fraction,      // a - floor(a)
  Modulo,        // per component as MathOp::Modulo
  Wrap,          // per component as MathOp::Wrap(a, b, c)
  Snap,          // per component as MathOp::Snap
  Sine,          // per component
  Cosine,        // per component
  Tangent,       // per component
};
constexpr int kVectorMathOpCount = int(VectorMathOp::Tangent) + 1;

// The Vector Math node: sets both outputs. DotProduct, Distance and Length set *value_out and
// zero *vector_out; the other ops set *vector_out and zero *value_out (Blender hides the output an
// op does not compute, and Cycles' constant folder starts both at 0). An op outside the
// enumeration zeroes both. Either pointer may be null.
void vector_math(VectorMathOp op, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, float scale,
                 glm::vec3* vector_out, float* value_out);

// Blender's identifier of an op ("MULTIPLY_ADD"), or "" for one outside the enumeration.
const char* math_op_name(MathOp op);
const char* vector_math_op_name(VectorMathOp op);

}  // namespace torrance::shader
