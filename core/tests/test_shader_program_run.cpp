// ShaderProgram::run's contract for every value it writes: finite, within +-1e30 (NaN and
// infinities to 0, larger magnitudes clamped), except where an op only moves finite registers about
// (Channel, Combine: ShaderOpInfo::copies), whose values pass through bit for bit.
#include <gtest/gtest.h>

#include "torrance/shader/shader_math.h"
#include "torrance/shader/shader_program.h"

#include <cmath>
#include <cstring>
#include <vector>

namespace torrance {
namespace {

ShaderInstruction instruction(ShaderOpcode op, int mode, int out, std::initializer_list<int> in) {
  ShaderInstruction ins;
  ins.op = op;
  ins.mode = uint8_t(mode);
  ins.out = int16_t(out);
  int k = 0;
  for (int r : in) ins.in[size_t(k++)] = int16_t(r);
  return ins;
}

TEST(ShaderProgramRun, OutputsAreClampedToFiniteValues) {
  const std::vector<glm::vec4> constants = {glm::vec4(1e30f, 0, 0, 0), glm::vec4(0.0f), glm::vec4(-1e30f, 0, 0, 0),
                                            glm::vec4(2.0f, 0, 0, 0)};
  const int mul = int(shader::MathOp::Multiply), div = int(shader::MathOp::Divide);
  const std::vector<ShaderInstruction> code = {
      instruction(ShaderOpcode::Math, mul, 4, {0, 0, 1}),  // 1e30 * 1e30: inf -> 0
      instruction(ShaderOpcode::Math, mul, 5, {0, 3, 1}),  // 2e30 -> 1e30
      instruction(ShaderOpcode::Math, mul, 6, {2, 3, 1}),  // -2e30 -> -1e30
      instruction(ShaderOpcode::Math, div, 7, {1, 1, 1}),  // 0 / 0: Cycles' safe divide, 0
  };
  const ShaderProgram program(constants, code, 8, 0);
  std::vector<glm::vec4> regs(8);
  program.run(ShaderGlobals{}, {}, regs.data());
  EXPECT_EQ(regs[4].x, 0.0f);
  EXPECT_EQ(regs[5].x, 1e30f);
  EXPECT_EQ(regs[6].x, -1e30f);
  EXPECT_EQ(regs[7].x, 0.0f);
  for (const glm::vec4& r : regs)
    for (int k = 0; k < 4; ++k) EXPECT_TRUE(std::isfinite(r[k]));
}

TEST(ShaderProgramRun, ChannelAndCombinePassValuesThroughBitForBit) {
  const glm::vec4 v(-0.0f, 1e-40f, -1e30f, 0.1f);  // a -0, a subnormal, the range's end
  const std::vector<ShaderInstruction> code = {
      instruction(ShaderOpcode::Channel, 0, 1, {0}), instruction(ShaderOpcode::Channel, 1, 2, {0}),
      instruction(ShaderOpcode::Channel, 2, 3, {0}), instruction(ShaderOpcode::Combine, 0, 4, {3, 2, 1})};
  const ShaderProgram program({v}, code, 5, 0);
  std::vector<glm::vec4> regs(5);
  program.run(ShaderGlobals{}, {}, regs.data());
  const glm::vec4 want(-1e30f, 1e-40f, -0.0f, 1.0f);
  EXPECT_EQ(std::memcmp(&regs[4], &want, sizeof want), 0) << regs[4].x << " " << regs[4].y << " " << regs[4].z;
}

}  // namespace
}  // namespace torrance
