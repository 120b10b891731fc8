// Blender's Noise, White Noise, Musgrave and Wave textures (core/src/shader/shader_noise.cpp) and Cycles'
// hash (shader_hash.h) as Cycles 3.4 computes them: the cases of
// core/tests/data/shader_noise_cases.json (Cycles' own renders; the Python twin's test checks
// them too), the hash's float mapping and -0's bits, Perlin noise's lattice zeros and range, the
// ops in a shader program (modes, outputs), and finite values over awkward inputs.
#include "json_table.h"
#include "torrance/shader/shader_hash.h"
#include "torrance/shader/shader_noise.h"
#include "torrance/shader/shader_program.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace torrance {
namespace {

using shader::MusgraveType;
using shader::WaveProfile;
using shader::WaveType;

using test::Json;

const Json& cases() { return test::json_table("shader_noise_cases.json"); }

// The table's rule: Cycles' CPU kernels sum the noise in another order (SSE/AVX2), so within
// 2e-6 max(1, |expected|).
bool close(float got, float expected) {
  return std::fabs(got - expected) <= 2e-6f * std::max(1.0f, std::fabs(expected));
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return int(i);
  throw std::runtime_error("unknown name " + name);
}

const std::vector<std::string> kMusgraveTypes = {"MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HYBRID_MULTIFRACTAL", "FBM",
                                                 "HETERO_TERRAIN"};
const std::vector<std::string> kWaveTypes = {"BANDS", "RINGS"};
const std::vector<std::string> kBandsDirections = {"X", "Y", "Z", "DIAGONAL"};
const std::vector<std::string> kRingsDirections = {"X", "Y", "Z", "SPHERICAL"};
const std::vector<std::string> kWaveProfiles = {"SIN", "SAW", "TRI"};

std::string describe(const Json& row) {
  std::ostringstream s;
  s << "[";
  for (size_t i = 0; i < row.items.size(); ++i) {
    const Json& v = row.items[i];
    if (i) s << ", ";
    if (v.kind == Json::Kind::Array)
      s << describe(v);
    else
      s << v.text;
  }
  s << "]";
  return s.str();
}

// ---- the hash ----

TEST(ShaderNoise, HashCases) {
  std::set<std::string> covered;
  for (const Json& row : cases()["hash"].items) {
    const std::string name = row[0].text;
    const Json& k = row[1];
    const uint32_t expected = row[2].uint();
    uint32_t got = 0;
    if (name == "hash_uint")
      got = shader::hash_uint(k[0].uint());
    else if (name == "hash_uint2")
      got = shader::hash_uint2(k[0].uint(), k[1].uint());
    else if (name == "hash_uint3")
      got = shader::hash_uint3(k[0].uint(), k[1].uint(), k[2].uint());
    else if (name == "hash_uint4")
      got = shader::hash_uint4(k[0].uint(), k[1].uint(), k[2].uint(), k[3].uint());
    else
      FAIL() << "unknown hash " << name;
    covered.insert(name);
    EXPECT_EQ(got, expected) << describe(row);
  }
  EXPECT_EQ(covered.size(), 4u);
}

TEST(ShaderNoise, HashFloatsByTheirBits) {
  // float(h) / 2^32: the top values round to 1 (float has 24 bits).
  EXPECT_EQ(shader::uint_to_float_incl(0u), 0.0f);
  EXPECT_EQ(shader::uint_to_float_incl(0xFFFFFFFFu), 1.0f);
  EXPECT_LT(shader::uint_to_float_excl(0xFFFFFFFFu), 1.0f);
  EXPECT_EQ(shader::hash_float_to_float(0.5f), float(shader::hash_uint(0x3F000000u)) * 0x1p-32f);
  // 0 and -0 hash differently (as in Cycles' kernel: a -0 computed at a hit hashes as -0; Blender's
  // constant inputs reach it as +0, which the add-on's reader does too).
  EXPECT_FLOAT_EQ(shader::hash_float_to_float(0.0f), 0.58242583f);
  EXPECT_FLOAT_EQ(shader::hash_float_to_float(-0.0f), 0.9026079f);
  // The vector-valued hashes: the key again with 1 and 2 appended, or its components rotated.
  const Vec3 k(0.3f, -1.5f, 7.0f);
  const Vec3 h3 = shader::hash_float3_to_float3(k);
  EXPECT_EQ(h3.x, shader::hash_float3_to_float(k));
  EXPECT_EQ(h3.y, shader::hash_float4_to_float(glm::vec4(k, 1.0f)));
  EXPECT_EQ(h3.z, shader::hash_float4_to_float(glm::vec4(k, 2.0f)));
  const glm::vec4 q(0.3f, -1.5f, 7.0f, 2.25f);
  const glm::vec4 h4 = shader::hash_float4_to_float4(q);
  EXPECT_EQ(h4.y, shader::hash_float4_to_float(glm::vec4(q.w, q.x, q.y, q.z)));
  EXPECT_EQ(h4.w, shader::hash_float4_to_float(glm::vec4(q.y, q.z, q.w, q.x)));
  const Vec3 h43 = shader::hash_float4_to_float3(q);
  EXPECT_EQ(h43.y, shader::hash_float4_to_float(glm::vec4(q.z, q.x, q.w, q.y)));
  EXPECT_EQ(h43.z, shader::hash_float4_to_float(glm::vec4(q.w, q.z, q.y, q.x)));
  EXPECT_EQ(shader::hash_float2_to_float2(Vec2(k)).y, shader::hash_float3_to_float(Vec3(k.x, k.y, 1.0f)));
  EXPECT_EQ(shader::hash_float_to_float3(2.5f).z, shader::hash_float2_to_float(Vec2(2.5f, 2.0f)));
}

// ---- the textures, case by case ----

TEST(ShaderNoise, NoiseTextureCases) {
  std::set<int> dims;
  for (const Json& row : cases()["noise"].items) {
    const int d = row[0].integer();
    dims.insert(d);
    const shader::NoiseTextureResult r =
        shader::noise_texture(d, row[1].vec3(), row[2].number, row[3].number, row[4].number, row[5].number,
                              row[6].number, true);
    const Vec3 color = row[8].vec3();
    EXPECT_TRUE(close(r.fac, row[7].number)) << describe(row) << ": fac " << r.fac;
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(close(r.color[k], color[k])) << describe(row) << ": color " << k;
    EXPECT_EQ(r.color.x, r.fac);
    EXPECT_EQ(shader::noise_texture(d, row[1].vec3(), row[2].number, row[3].number, row[4].number,
                                    row[5].number, row[6].number, false)
                  .fac,
              r.fac);
  }
  EXPECT_EQ(dims, (std::set<int>{1, 2, 3, 4}));
}

TEST(ShaderNoise, WhiteNoiseCasesExactly) {
  std::set<int> dims;
  for (const Json& row : cases()["white_noise"].items) {
    const int d = row[0].integer();
    dims.insert(d);
    const Vec3 v = row[1].vec3();
    const float w = row[2].number;
    EXPECT_EQ(shader::white_noise_value(d, v, w), row[3].number) << describe(row);
    EXPECT_EQ(shader::white_noise_color(d, v, w), row[4].vec3()) << describe(row);
  }
  EXPECT_EQ(dims, (std::set<int>{1, 2, 3, 4}));
}

TEST(ShaderNoise, MusgraveCases) {
  std::set<std::pair<int, int>> covered;
  for (const Json& row : cases()["musgrave"].items) {
    const int type = index_of(kMusgraveTypes, row[0].text), d = row[1].integer();
    covered.insert({type, d});
    const float got = shader::musgrave(MusgraveType(type), d, row[2].vec3(), row[3].number, row[4].number,
                                       row[5].number, row[6].number, row[7].number, row[8].number,
                                       row[9].number);
    EXPECT_TRUE(close(got, row[10].number)) << describe(row) << ": " << got;
  }
  EXPECT_EQ(covered.size(), size_t(shader::kMusgraveTypes * 4));
}

TEST(ShaderNoise, WaveCases) {
  std::set<int> covered;
  for (const Json& row : cases()["wave"].items) {
    const int type = index_of(kWaveTypes, row[0].text);
    const int direction = index_of(type == 0 ? kBandsDirections : kRingsDirections, row[1].text);
    const int profile = index_of(kWaveProfiles, row[2].text);
    covered.insert((type * 4 + direction) * 3 + profile);
    const float got = shader::wave(WaveType(type), direction, WaveProfile(profile), row[3].vec3(), row[4].number,
                                   row[5].number, row[6].number, row[7].number, row[8].number,
                                   row[9].number);
    EXPECT_TRUE(close(got, row[10].number)) << describe(row) << ": " << got;
  }
  EXPECT_EQ(covered.size(), size_t(shader::kWaveModes));
}

// ---- Perlin noise's shape ----

TEST(ShaderNoise, PerlinIsZeroOnTheLatticeAndBounded) {
  EXPECT_EQ(shader::snoise(3.0f), 0.0f);
  EXPECT_EQ(shader::snoise(Vec2(-2.0f, 5.0f)), 0.0f);
  EXPECT_EQ(shader::snoise(Vec3(1.0f, 0.0f, -7.0f)), 0.0f);
  EXPECT_EQ(shader::snoise(glm::vec4(0.0f, 4.0f, -1.0f, 9.0f)), 0.0f);
  EXPECT_EQ(shader::unoise(Vec3(2.0f, 2.0f, 2.0f)), 0.5f);
  float lo = 1.0f, hi = -1.0f;
  for (int i = 0; i < 4000; ++i) {
    const float t = float(i) * 0.0123f - 20.0f;
    for (const float s : {shader::snoise(t), shader::snoise(Vec2(t, 0.37f * t)),
                          shader::snoise(Vec3(t, -0.61f * t, 0.2f * t + 0.5f)),
                          shader::snoise(glm::vec4(t, 0.7f * t, -0.3f * t, 0.11f * t))}) {
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
  }
  EXPECT_GT(lo, -1.05f);
  EXPECT_LT(hi, 1.05f);
  EXPECT_LT(lo, -0.5f);
  EXPECT_GT(hi, 0.5f);
}

TEST(ShaderNoise, CellsOutsideIntBecomeIntMinAsOnX86) {
  // Cycles converts floor(x) to int with cvttss2si (INT_MIN outside int32), and then, by the bits,
  // all those cells are one; the fraction x - floor(x) of such x is 0: noise 0 (and inf gives NaN,
  // which snoise sets to 0).
  EXPECT_EQ(shader::snoise(3e9f), 0.0f);
  EXPECT_EQ(shader::snoise(Vec3(-5e9f, 1e20f, 3.0f)), 0.0f);
  EXPECT_EQ(shader::snoise(std::numeric_limits<float>::infinity()), 0.0f);
  EXPECT_EQ(shader::unoise(Vec2(std::numeric_limits<float>::infinity(), 0.5f)), 0.5f);
}

// ---- the ops in a program ----

glm::vec4 run_op(ShaderOpcode op, int mode, int flags, const std::vector<glm::vec4>& args) {
  ShaderInstruction ins;
  ins.op = op;
  ins.mode = uint8_t(mode);
  ins.flags = uint8_t(flags);
  ins.out = int16_t(args.size());
  for (size_t k = 0; k < args.size(); ++k) ins.in[k] = int16_t(k);
  const ShaderProgram program(args, {ins}, int(args.size()) + 1, 0);
  std::vector<glm::vec4> regs(args.size() + 1);
  program.run(ShaderGlobals{}, {}, regs.data());
  return regs.back();
}

glm::vec4 scalar(float v) { return glm::vec4(v, 0.0f, 0.0f, 0.0f); }

TEST(ShaderNoise, OpsInAProgram) {
  const glm::vec4 vector(0.3f, 1.7f, -2.2f, 0.0f);
  const std::vector<glm::vec4> noise_args = {vector,          scalar(0.8f), scalar(2.5f),
                                             scalar(3.5f),    scalar(0.6f), scalar(0.4f)};
  for (int mode = 0; mode < 4; ++mode) {
    const shader::NoiseTextureResult r = shader::noise_texture(mode + 1, Vec3(vector), 0.8f, 2.5f, 3.5f, 0.6f, 0.4f, true);
    EXPECT_EQ(run_op(ShaderOpcode::Noise, mode, 0, noise_args), glm::vec4(r.fac, 0.0f, 0.0f, 0.0f));
    EXPECT_EQ(run_op(ShaderOpcode::Noise, mode, 1, noise_args), glm::vec4(r.color, 1.0f));
    const std::vector<glm::vec4> wn_args = {vector, scalar(0.8f)};
    EXPECT_EQ(run_op(ShaderOpcode::WhiteNoise, mode, 0, wn_args),
              scalar(shader::white_noise_value(mode + 1, Vec3(vector), 0.8f)));
    EXPECT_EQ(run_op(ShaderOpcode::WhiteNoise, mode, 1, wn_args),
              glm::vec4(shader::white_noise_color(mode + 1, Vec3(vector), 0.8f), 1.0f));
  }
  const std::vector<glm::vec4> musgrave_args = {vector,       scalar(0.8f), scalar(1.5f), scalar(4.5f),
                                                scalar(1.2f), scalar(2.1f), scalar(0.9f), scalar(1.3f)};
  for (int mode = 0; mode < shader::kMusgraveModes; ++mode)
    EXPECT_EQ(run_op(ShaderOpcode::Musgrave, mode, 0, musgrave_args),
              scalar(shader::musgrave(MusgraveType(mode / 4), mode % 4 + 1, Vec3(vector), 0.8f, 1.5f, 4.5f, 1.2f, 2.1f,
                                      0.9f, 1.3f)))
        << "mode " << mode;
  const std::vector<glm::vec4> wave_args = {vector,       scalar(1.3f), scalar(2.0f), scalar(2.0f),
                                            scalar(1.0f), scalar(0.5f), scalar(0.25f)};
  for (int mode = 0; mode < shader::kWaveModes; ++mode) {
    const int shape = mode / 3;
    const float f = shader::wave(WaveType(shape / 4), shape % 4, WaveProfile(mode % 3), Vec3(vector), 1.3f, 2.0f,
                                 2.0f, 1.0f, 0.5f, 0.25f);
    EXPECT_EQ(run_op(ShaderOpcode::Wave, mode, 0, wave_args), scalar(f)) << "mode " << mode;
    EXPECT_EQ(run_op(ShaderOpcode::Wave, mode, 1, wave_args), glm::vec4(f, f, f, 1.0f)) << "mode " << mode;
  }
}

TEST(ShaderNoise, OpShapes) {
  EXPECT_EQ(int(ShaderOpcode::Noise), 32);
  EXPECT_EQ(int(ShaderOpcode::WhiteNoise), 33);
  EXPECT_EQ(int(ShaderOpcode::Musgrave), 34);
  EXPECT_EQ(int(ShaderOpcode::Wave), 35);
  const std::pair<ShaderOpcode, std::pair<int, int>> shapes[] = {{ShaderOpcode::Noise, {6, 4}},
                                                                  {ShaderOpcode::WhiteNoise, {2, 4}},
                                                                  {ShaderOpcode::Musgrave, {8, 20}},
                                                                  {ShaderOpcode::Wave, {7, 24}}};
  for (const auto& [op, shape] : shapes) {
    const ShaderOpInfo info = shader_op_info(op);
    EXPECT_EQ(info.inputs, shape.first) << int(op);
    EXPECT_EQ(info.modes, shape.second) << int(op);
    EXPECT_FALSE(info.data);
    EXPECT_NE(info.run, nullptr);
  }
  EXPECT_THROW(run_op(ShaderOpcode::Noise, 4, 0, std::vector<glm::vec4>(6, glm::vec4(0.0f))), std::invalid_argument);
  EXPECT_THROW(run_op(ShaderOpcode::Wave, 24, 0, std::vector<glm::vec4>(7, glm::vec4(0.0f))), std::invalid_argument);
}

TEST(ShaderNoise, FiniteOverAwkwardInputs) {
  const float awkward[] = {0.0f, -0.0f, 1e-30f, -1e-30f, 1.0f, -3.5f, 1e7f, -1e7f, 1e30f, -1e30f};
  for (const float a : awkward)
    for (const float b : awkward) {
      const Vec3 v(a, b, 0.5f * a - b);
      for (int d = 1; d <= 4; ++d) {
        // Scales, details and distortions within the node's ranges; coordinates anything.
        const shader::NoiseTextureResult r = shader::noise_texture(d, v, b, 5.0f, 15.0f, 0.5f, 1000.0f, true);
        EXPECT_TRUE(std::isfinite(r.fac) && std::isfinite(r.color.y) && std::isfinite(r.color.z)) << a << " " << b;
        EXPECT_TRUE(std::isfinite(shader::white_noise_value(d, v, a)));
        EXPECT_TRUE(std::isfinite(shader::musgrave(MusgraveType::FBM, d, v, b, 5.0f, 15.0f, 1.0f, 2.0f, 0.0f, 1.0f)));
      }
      // Any input: the program keeps its values finite (Cycles' NaNs, e.g. sin(inf), become 0).
      const std::vector<glm::vec4> args = {glm::vec4(v, 0.0f), scalar(a), scalar(b), scalar(a),
                                           scalar(b),          scalar(a), scalar(b)};
      for (int mode = 0; mode < shader::kWaveModes; ++mode) {
        const glm::vec4 out = run_op(ShaderOpcode::Wave, mode, 1, args);
        EXPECT_TRUE(std::isfinite(out.x) && std::isfinite(out.y) && std::isfinite(out.z));
      }
      const std::vector<glm::vec4> margs = {glm::vec4(v, 0.0f), scalar(a), scalar(b), scalar(a),
                                            scalar(b),          scalar(a), scalar(b), scalar(a)};
      for (int mode = 0; mode < shader::kMusgraveModes; ++mode)
        EXPECT_TRUE(std::isfinite(run_op(ShaderOpcode::Musgrave, mode, 0, margs).x));
    }
}

}  // namespace
}  // namespace torrance
