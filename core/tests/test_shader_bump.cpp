// The Bump and Normal Map formulas (core/src/shader/shader_bump.cpp) as Cycles 3.4 computes them: a
// flat height and zero differentials leave the normal, a slope tilts it against the gradient by
// Distance (Invert: the other way), Strength mixes, degenerate inputs stay finite.
#include "torrance/scene/scene.h"
#include "torrance/shader/shader_bump.h"
#include "torrance/shader/shader_program.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace torrance {
namespace {

using shader::bump_normal;

TEST(ShaderBump, FlatHeightOrZeroDifferentialsKeepTheNormal) {
  const Vec3 n(0, 0, 1), dx(0.01f, 0, 0), dy(0, 0.01f, 0);
  EXPECT_EQ(bump_normal(n, dx, dy, 0.5f, 0.5f, 0.5f, 1.0f, 1.0f), n);
  EXPECT_EQ(bump_normal(n, Vec3(0.0f), Vec3(0.0f), 0.5f, 0.7f, 0.1f, 1.0f, 1.0f), n);
}

TEST(ShaderBump, SlopeTiltsAgainstTheGradientByDistance) {
  const Vec3 n(0, 0, 1), dx(0.01f, 0, 0), dy(0, 0.01f, 0);
  // h = x: slope 1 along x; n' ~ (-distance, 0, 1).
  const Vec3 a = bump_normal(n, dx, dy, 0.0f, 0.01f, 0.0f, 0.5f, 1.0f);
  EXPECT_NEAR(a.x, -0.5f / std::sqrt(1.25f), 1e-5f);
  EXPECT_NEAR(a.z, 1.0f / std::sqrt(1.25f), 1e-5f);
  const Vec3 inverted = bump_normal(n, dx, dy, 0.0f, 0.01f, 0.0f, -0.5f, 1.0f);
  EXPECT_NEAR(inverted.x, -a.x, 1e-6f);
  // Swapped differentials (a negative determinant) give the same normal.
  const Vec3 b = bump_normal(n, dy, dx, 0.0f, 0.0f, 0.01f, 0.5f, 1.0f);
  EXPECT_NEAR(b.x, a.x, 1e-5f);
  // Strength 0.5: halfway, renormalized.
  const Vec3 half = bump_normal(n, dx, dy, 0.0f, 0.01f, 0.0f, 0.5f, 0.5f);
  const Vec3 expect = glm::normalize(0.5f * a + 0.5f * n);
  EXPECT_NEAR(half.x, expect.x, 1e-5f);
  EXPECT_NEAR(half.z, expect.z, 1e-5f);
}

TEST(ShaderBump, DegenerateInputsStayFinite) {
  const float inf = std::numeric_limits<float>::infinity();
  const Vec3 n(0, 0, 1);
  for (float h : {0.0f, 1e30f, -1e30f, inf})
    for (float w : {0.0f, 1e-30f, 1e30f}) {
      const Vec3 out = bump_normal(n, Vec3(w, 0, 0), Vec3(0, w, 0), 0.0f, h, -h, 1e30f, 1.0f);
      EXPECT_TRUE(std::isfinite(out.x) && std::isfinite(out.y) && std::isfinite(out.z)) << h << " " << w;
    }
  Vec3 a, b;
  shader::differential_axes(Vec3(1, 1, 1) / std::sqrt(3.0f), a, b);
  EXPECT_NEAR(glm::length(a), 1.0f, 1e-5f);
  const Vec3 m = shader::tangent_normal_map(Vec3(0.5f, 0.5f, 1.0f), n, Vec3(0.0f), 1.0f, 1.0f);
  EXPECT_EQ(m, n);  // no tangent: the normal
  const Vec3 t = shader::tangent_normal_map(Vec3(1.0f, 0.5f, 0.5f), n, Vec3(1, 0, 0), 1.0f, 1.0f);
  EXPECT_NEAR(t.x, 1.0f, 1e-6f);
}

// Cycles 4.x's tangent-space Strength scales the mapped colour's tangent components and moves
// its normal component from 1: Strength 1 is 3.4's map, 0 the surface normal, 0.5 of the colour
// (1, 0.5, 0.5) (mapped (1, 0, 0)) is normalize(0.5, 0, 0.5); 3.4 mixes normals instead.
TEST(ShaderBump, Cycles4NormalMapStrengthScalesTheColour) {
  const Vec3 n(0, 0, 1), t(1, 0, 0), c(1.0f, 0.5f, 0.5f);
  const Vec3 full = shader::tangent_normal_map(c, n, t, 1.0f, 1.0f, true);
  const Vec3 full34 = shader::tangent_normal_map(c, n, t, 1.0f, 1.0f);
  EXPECT_NEAR(glm::length(full - full34), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(shader::tangent_normal_map(c, n, t, 1.0f, 0.0f, true) - n), 0.0f, 1e-6f);
  const Vec3 half = shader::tangent_normal_map(c, n, t, 1.0f, 0.5f, true);
  EXPECT_NEAR(half.x, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(half.z, std::sqrt(0.5f), 1e-6f);
  const Vec3 half34 = shader::tangent_normal_map(c, n, t, 1.0f, 0.5f);  // normalize(n + (m - n) / 2)
  EXPECT_NEAR(half34.x, std::sqrt(0.5f), 1e-6f);
  const Vec3 strong = shader::tangent_normal_map(Vec3(0.8f, 0.5f, 0.6f), n, t, 1.0f, 0.7f, true);
  const Vec3 strong34 = shader::tangent_normal_map(Vec3(0.8f, 0.5f, 0.6f), n, t, 1.0f, 0.7f);
  EXPECT_GT(strong.z, strong34.z);  // 4.x keeps more of the surface normal at a shallow colour
}

// A program reads the ray differentials where it has a Bump op or instructions at the offset
// hits (what lets the integrator skip making them for every other program).
TEST(ShaderBump, ProgramsSayWhetherTheyReadDifferentials) {
  const std::vector<glm::vec4> constants(6, glm::vec4(0.5f));
  ShaderInstruction bump;
  bump.op = ShaderOpcode::Bump;
  bump.out = 6;
  for (int k = 0; k < 7; ++k) bump.in[size_t(k)] = int16_t(k % 6);
  EXPECT_TRUE(ShaderProgram(constants, {bump}, 7, 0).reads_differentials());
  ShaderInstruction uv;  // TexCoordUV at the hit, then at the hit moved by dx
  uv.out = 6;
  EXPECT_FALSE(ShaderProgram(constants, {uv}, 7, 0).reads_differentials());
  uv.offset = 1;
  EXPECT_TRUE(ShaderProgram(constants, {uv}, 7, 0).reads_differentials());
  EXPECT_FALSE(ShaderProgram(constants, {}, 6, 0).reads_differentials());
}

// Cycles 4.3+'s Filter Width: the heights' offset hits lie at width times the ray differentials
// (a UV read at offset 1 sees uv + width duv/dx), the bumped normal divides the heights' change
// by it; a program has one width, a constant.
TEST(ShaderBump, FilterWidthMovesTheOffsetHits) {
  // Constants: 0 Strength 1, 1 Distance 0.1, 2 the width 0.1, 3 the normal (0, 0, 1).
  const std::vector<glm::vec4> constants = {glm::vec4(1.0f), glm::vec4(0.1f), glm::vec4(0.1f),
                                            glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)};
  std::vector<ShaderInstruction> code(4);
  for (int k = 0; k < 3; ++k) {  // the UV at the hit and at its offsets: registers 4, 5, 6
    code[size_t(k)].out = int16_t(4 + k);
    code[size_t(k)].offset = uint8_t(k);
  }
  ShaderInstruction& bump = code[3];
  bump.op = ShaderOpcode::Bump;
  bump.in = {0, 1, 4, 5, 6, 3, 2};
  bump.flags = shader::kBumpCycles4;
  bump.out = 7;
  ShaderGlobals g;
  g.uv = Vec2(0.25f, 0.5f);
  g.dpdx = Vec3(0.01f, 0.0f, 0.0f), g.dpdy = Vec3(0.0f, 0.01f, 0.0f);
  g.duvdx = Vec2(0.02f, 0.0f), g.duvdy = Vec2(0.0f, 0.02f);
  std::array<glm::vec4, 8> regs{};
  const ShaderProgram narrow(constants, code, 8, 0);
  narrow.run(g, {}, regs.data());
  EXPECT_FLOAT_EQ(regs[5].x, 0.25f + 0.1f * 0.02f);
  EXPECT_FLOAT_EQ(regs[6].y, 0.5f + 0.1f * 0.02f);
  // Height u: its slope 2 per unit of x (du/dx = 0.02 / 0.01), whatever the width.
  const Vec3 expected = glm::normalize(Vec3(-0.1f * 2.0f, 0.0f, 1.0f));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(regs[7][k], expected[k], 1e-5f) << k;
  std::vector<glm::vec4> wide = constants;
  wide[2] = glm::vec4(1.0f);
  const ShaderProgram cycles42(wide, code, 8, 0);
  cycles42.run(g, {}, regs.data());
  EXPECT_FLOAT_EQ(regs[5].x, 0.25f + 0.02f);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(regs[7][k], expected[k], 1e-5f) << k;
  // A width read from a computed register, or two Bumps of different widths: refused.
  std::vector<ShaderInstruction> computed = code;
  computed[3].in[6] = 4;
  EXPECT_THROW(ShaderProgram(constants, computed, 8, 0), std::invalid_argument);
  std::vector<ShaderInstruction> two = code;
  two.push_back(bump);
  two.back().in[6] = 0;  // width 1
  two.back().out = 8;
  EXPECT_THROW(ShaderProgram(constants, two, 9, 0), std::invalid_argument);
  two.back().in[6] = 2;
  EXPECT_NO_THROW(ShaderProgram(constants, two, 9, 0));
}

// A program says which globals beyond the hit's basics it reads (what shader_globals fills).
TEST(ShaderBump, ProgramsSayWhatGlobalsTheyRead) {
  const std::vector<glm::vec4> constants(6, glm::vec4(0.5f));
  auto reads = [&](ShaderOpcode op, uint8_t mode = 0, uint8_t offset = 0) {
    ShaderInstruction ins;
    ins.op = op;
    ins.mode = mode;
    ins.offset = offset;
    ins.out = 6;
    return ShaderProgram(constants, {ins}, 7, 0).globals_read();
  };
  EXPECT_EQ(ShaderProgram(constants, {}, 6, 0).globals_read(), 0);
  EXPECT_EQ(reads(ShaderOpcode::TexCoordUV), 0);
  EXPECT_EQ(reads(ShaderOpcode::TexCoordUV, 0, 1), kReadsDifferentials);
  EXPECT_EQ(reads(ShaderOpcode::Attribute), kReadsAttributes);
  EXPECT_EQ(reads(ShaderOpcode::Attribute, 0, 2), kReadsAttributes | kReadsDifferentials);
  EXPECT_EQ(reads(ShaderOpcode::Tangent), kReadsTangent);
  EXPECT_EQ(reads(ShaderOpcode::NormalMap), kReadsTangent);
  EXPECT_EQ(reads(ShaderOpcode::Wireframe), kReadsCorners);
  EXPECT_EQ(reads(ShaderOpcode::Wireframe, 1), kReadsCorners | kReadsDifferentials);  // Pixel Size
  // shader_globals fills only what it is told to.
  SurfaceHit hit;
  hit.tangent = Vec3(1, 0, 0);
  hit.corners[1] = Vec3(2, 0, 0);
  hit.num_attributes = 3;
  const ShaderGlobals none = shader_globals(hit, Vec3(0, 0, -1), 0.0f, 1.0f, 0);
  EXPECT_EQ(none.tangent, Vec3(0.0f));
  EXPECT_EQ(none.corners[1], Vec3(0.0f));
  EXPECT_EQ(none.num_attributes, 0);
  const ShaderGlobals all = shader_globals(hit, Vec3(0, 0, -1), 0.0f, 1.0f);
  EXPECT_EQ(all.tangent, hit.tangent);
  EXPECT_EQ(all.corners[1], hit.corners[1]);
  EXPECT_EQ(all.num_attributes, 3);
}

}  // namespace
}  // namespace torrance
