#include "torrance/shader/shader_math.h"

#include <cfloat>
#include <cmath>

namespace torrance::shader {

namespace {

// Every step below is one float operation in the order Cycles does it, so results round as Cycles'
// do (the build has no -ffast-math to reorder them).

float divide_or_zero(float a, float b) { return b != 0.0f ? a / b : 0.0f; }

// Cycles' clamp: max then min, each a comparison, so NaN clamps to the lower bound.
float clamp_to(float v, float lo, float hi) {
  const float at_least_lo = v > lo ? v : lo;
  return at_least_lo < hi ? at_least_lo : hi;
}

float fract(float x) { return x - std::floor(x); }

// Cycles tests "is b an integer" as b != (int)b, which its CPU kernels (-ffast-math) evaluate as a
// truncation in float: integral exponents beyond int's range count as integers too (Blender
// 3.4.1 renders pow(-1, 3e9) = 1 and pow(-2, 1e30) = inf, not the 0 of an x86 int conversion).
float power(float a, float b) {
  if (a < 0.0f && b != std::trunc(b)) return 0.0f;  // a negative base only to integer powers
  return std::pow(a, b);                            // the CPU's powf: pow(0, -1) is +inf
}

float logarithm(float a, float base) {
  if (a <= 0.0f || base <= 0.0f) return 0.0f;
  return divide_or_zero(std::log(a), std::log(base));  // base 1: log 1 = 0 divides to 0
}

float inverse_sqrt(float a) { return a > 0.0f ? 1.0f / std::sqrt(a) : 0.0f; }

float sign_of(float a) {
  if (a == 0.0f) return 0.0f;
  return a < 0.0f ? -1.0f : 1.0f;  // NaN gives 1, as Cycles' signf
}

float smooth_min(float a, float b, float k) {
  if (k == 0.0f) return std::fmin(a, b);
  const float h = std::fmax(k - std::fabs(a - b), 0.0f) / k;
  return std::fmin(a, b) - h * h * h * k * (1.0f / 6.0f);
}

float modulo(float a, float b) { return b != 0.0f ? std::fmod(a, b) : 0.0f; }

float floored_modulo(float a, float b) { return b != 0.0f ? a - std::floor(a / b) * b : 0.0f; }

// Note the argument order of the node: the value, then the upper bound, then the lower one.
float wrap(float v, float upper, float lower) {
  const float range = upper - lower;
  if (range == 0.0f) return lower;
  return v - range * std::floor((v - lower) / range);
}

float snap(float a, float increment) { return std::floor(divide_or_zero(a, increment)) * increment; }

float ping_pong(float a, float scale) {
  if (scale == 0.0f) return 0.0f;
  return std::fabs(fract((a - scale) / (scale * 2.0f)) * scale * 2.0f - scale);
}

float trunc_toward_zero(float a) { return a >= 0.0f ? std::floor(a) : std::ceil(a); }

float compare(float a, float b, float epsilon) {
  return (a == b || std::fabs(a - b) <= std::fmax(epsilon, FLT_EPSILON)) ? 1.0f : 0.0f;
}

// Cycles' float3 helpers, component by component in its order.
float dot3(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
float length3(const Vec3& a) { return std::sqrt(dot3(a, a)); }

// Unguarded, as Cycles' normalize(): a zero vector gives 0 / 0.
Vec3 unit_of(const Vec3& a) {
  const float len = length3(a);
  return Vec3(a.x / len, a.y / len, a.z / len);
}

Vec3 reflect(const Vec3& incident, const Vec3& normal) {
  const Vec3 n = unit_of(normal);
  const float d = dot3(incident, n);
  return incident - (2.0f * n) * d;
}

Vec3 refract(const Vec3& incident, const Vec3& unit_normal, float eta) {
  const float d = dot3(unit_normal, incident);
  const float k = 1.0f - eta * eta * (1.0f - d * d);
  if (k < 0.0f) return Vec3(0.0f);  // total internal reflection
  return eta * incident - (eta * d + std::sqrt(k)) * unit_normal;
}

Vec3 project(const Vec3& a, const Vec3& onto) {
  const float len_sq = dot3(onto, onto);
  if (len_sq == 0.0f) return Vec3(0.0f);
  return (dot3(a, onto) / len_sq) * onto;
}

// Multiplies by the reciprocal length, as Cycles' safe_normalize (rounds unlike a / |a|).
Vec3 normalize_or_keep(const Vec3& a) {
  const float len = length3(a);
  return len != 0.0f ? a * (1.0f / len) : a;
}

template <typename F>
Vec3 per_component(const Vec3& a, F f) {
  return Vec3(f(a.x), f(a.y), f(a.z));
}

template <typename F>
Vec3 per_component(const Vec3& a, const Vec3& b, F f) {
  return Vec3(f(a.x, b.x), f(a.y, b.y), f(a.z, b.z));
}

constexpr const char* kMathOpNames[kMathOpCount] = {
    "ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "POWER", "LOGARITHM", "SQRT", "INVERSE_SQRT",
    "ABSOLUTE", "EXPONENT", "MINIMUM", "MAXIMUM", "LESS_THAN", "GREATER_THAN", "SIGN", "COMPARE", "SMOOTH_MIN",
    "SMOOTH_MAX", "ROUND", "FLOOR", "CEIL", "TRUNC", "FRACT", "MODULO", "FLOORED_MODULO", "WRAP", "SNAP",
    "PINGPONG", "SINE", "COSINE", "TANGENT", "ARCSINE", "ARCCOSINE", "ARCTANGENT", "ARCTAN2", "SINH", "COSH",
    "TANH", "RADIANS", "DEGREES"};

constexpr const char* kVectorMathOpNames[kVectorMathOpCount] = {
    "ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "CROSS_PRODUCT", "PROJECT", "REFLECT", "REFRACT",
    "FACEFORWARD", "DOT_PRODUCT", "DISTANCE", "LENGTH", "SCALE", "NORMALIZE", "ABSOLUTE", "MINIMUM", "MAXIMUM",
    "FLOOR", "CEIL", "FRACTION", "MODULO", "WRAP", "SNAP", "SINE", "COSINE", "TANGENT"};

}  // namespace

float math(MathOp op, float a, float b, float c) {
  switch (op) {
    case MathOp::Add: return a + b;
    case MathOp::Subtract: return a - b;
    case MathOp::Multiply: return a * b;
    case MathOp::Divide: return divide_or_zero(a, b);
    case MathOp::MultiplyAdd: return a * b + c;
    case MathOp::Power: return power(a, b);
    case MathOp::Logarithm: return logarithm(a, b);
    case MathOp::Sqrt: return std::sqrt(a > 0.0f ? a : 0.0f);
    case MathOp::InverseSqrt: return inverse_sqrt(a);
    case MathOp::Absolute: return std::fabs(a);
    case MathOp::Exponent: return std::exp(a);
    case MathOp::Minimum: return std::fmin(a, b);
    case MathOp::Maximum: return std::fmax(a, b);
    case MathOp::LessThan: return a < b ? 1.0f : 0.0f;
    case MathOp::GreaterThan: return a > b ? 1.0f : 0.0f;
    case MathOp::Sign: return sign_of(a);
    case MathOp::Compare: return compare(a, b, c);
    case MathOp::SmoothMin: return smooth_min(a, b, c);
    case MathOp::SmoothMax: return -smooth_min(-a, -b, c);
    case MathOp::Round: return std::floor(a + 0.5f);
    case MathOp::Floor: return std::floor(a);
    case MathOp::Ceil: return std::ceil(a);
    case MathOp::Trunc: return trunc_toward_zero(a);
    case MathOp::Fract: return fract(a);
    case MathOp::Modulo: return modulo(a, b);
    case MathOp::FlooredModulo: return floored_modulo(a, b);
    case MathOp::Wrap: return wrap(a, b, c);
    case MathOp::Snap: return snap(a, b);
    case MathOp::PingPong: return ping_pong(a, b);
    case MathOp::Sine: return std::sin(a);
    case MathOp::Cosine: return std::cos(a);
    case MathOp::Tangent: return std::tan(a);
    case MathOp::Arcsine: return std::asin(clamp_to(a, -1.0f, 1.0f));
    case MathOp::Arccosine: return std::acos(clamp_to(a, -1.0f, 1.0f));
    case MathOp::Arctangent: return std::atan(a);
    case MathOp::Arctan2: return std::atan2(a, b);
    case MathOp::Sinh: return std::sinh(a);
    case MathOp::Cosh: return std::cosh(a);
    case MathOp::Tanh: return std::tanh(a);
    case MathOp::Radians: return a * (kPi / 180.0f);
    case MathOp::Degrees: return a * (180.0f / kPi);
  }
  return 0.0f;
}

float clamp_unit(float v) { return clamp_to(v, 0.0f, 1.0f); }

void vector_math(VectorMathOp op, const Vec3& a, const Vec3& b, const Vec3& c, float scale, Vec3* vector_out,
                 float* value_out) {
  Vec3 vector(0.0f);
  float value = 0.0f;
  switch (op) {
    case VectorMathOp::Add: vector = a + b; break;
    case VectorMathOp::Subtract: vector = a - b; break;
    case VectorMathOp::Multiply: vector = a * b; break;
    case VectorMathOp::Divide: vector = per_component(a, b, divide_or_zero); break;
    case VectorMathOp::MultiplyAdd: vector = a * b + c; break;
    case VectorMathOp::CrossProduct:
      vector = Vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
      break;
    case VectorMathOp::Project: vector = project(a, b); break;
    case VectorMathOp::Reflect: vector = reflect(a, b); break;
    case VectorMathOp::Refract: vector = refract(a, unit_of(b), scale); break;
    case VectorMathOp::Faceforward: vector = dot3(c, b) < 0.0f ? a : -a; break;
    case VectorMathOp::DotProduct: value = dot3(a, b); break;
    case VectorMathOp::Distance: value = length3(a - b); break;
    case VectorMathOp::Length: value = length3(a); break;
    case VectorMathOp::Scale: vector = a * scale; break;
    case VectorMathOp::Normalize: vector = normalize_or_keep(a); break;
    case VectorMathOp::Absolute: vector = per_component(a, [](float x) { return std::fabs(x); }); break;
    case VectorMathOp::Minimum:
      vector = per_component(a, b, [](float x, float y) { return x < y ? x : y; });
      break;
    case VectorMathOp::Maximum:
      vector = per_component(a, b, [](float x, float y) { return x > y ? x : y; });
      break;
    case VectorMathOp::Floor: vector = per_component(a, [](float x) { return std::floor(x); }); break;
    case VectorMathOp::Ceil: vector = per_component(a, [](float x) { return std::ceil(x); }); break;
    case VectorMathOp::Fraction: vector = per_component(a, fract); break;
    case VectorMathOp::Modulo: vector = per_component(a, b, modulo); break;
    case VectorMathOp::Wrap: vector = Vec3(wrap(a.x, b.x, c.x), wrap(a.y, b.y, c.y), wrap(a.z, b.z, c.z)); break;
    case VectorMathOp::Snap: vector = per_component(a, b, snap); break;
    case VectorMathOp::Sine: vector = per_component(a, [](float x) { return std::sin(x); }); break;
    case VectorMathOp::Cosine: vector = per_component(a, [](float x) { return std::cos(x); }); break;
    case VectorMathOp::Tangent: vector = per_component(a, [](float x) { return std::tan(x); }); break;
  }
  if (vector_out) *vector_out = vector;
  if (value_out) *value_out = value;
}

const char* math_op_name(MathOp op) { return int(op) < kMathOpCount ? kMathOpNames[int(op)] : ""; }

const char* vector_math_op_name(VectorMathOp op) {
  return int(op) < kVectorMathOpCount ? kVectorMathOpNames[int(op)] : "";
}

}  // namespace torrance::shader
