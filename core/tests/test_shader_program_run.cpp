// ShaderProgram::run's contract for every value it writes: finite, within +-1e30 (NaN and
// infinities to 0, larger magnitudes clamped), except where an op only moves finite registers about
// (Channel, Combine: ShaderOpInfo::copies), whose values pass through bit for bit. run() does the
// moves in its loop, three Channels and a Combine after them as one step (Step::kSeparateCombine):
// random programs of them agree bit for bit with the ops run one by one through shader_op_info.
#include <gtest/gtest.h>

#include "torrance/shader/shader_math.h"
#include "torrance/shader/shader_program.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
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

// Vector Math gives each lane its own case: infinities (1e30 * 1e30) and NaN (a cross product's
// inf - inf) to 0, 2e30 clamped, -0 and a subnormal kept.
TEST(ShaderProgramRun, ClampOfNonFiniteAndOutOfRangeLanes) {
  const std::vector<glm::vec4> constants = {glm::vec4(1e30f, -1e30f, 2e30f, 0.0f), glm::vec4(1e30f, 1e30f, 1.0f, 0.0f),
                                            glm::vec4(-0.0f, 1e-40f, -2e30f, 0.0f), glm::vec4(1.0f, 1.0f, 1.0f, 0.0f),
                                            glm::vec4(1e30f, 1e30f, 1e30f, 0.0f)};
  const int mul = int(shader::VectorMathOp::Multiply), cross = int(shader::VectorMathOp::CrossProduct);
  const std::vector<ShaderInstruction> code = {instruction(ShaderOpcode::VectorMath, mul, 5, {0, 1, 0, 0}),
                                               instruction(ShaderOpcode::VectorMath, mul, 6, {2, 3, 0, 0}),
                                               instruction(ShaderOpcode::VectorMath, cross, 7, {4, 4, 0, 0})};
  const ShaderProgram program(constants, code, 8, 0);
  std::vector<glm::vec4> regs(8);
  program.run(ShaderGlobals{}, {}, regs.data());
  const glm::vec4 want[3] = {glm::vec4(0.0f, 0.0f, 1e30f, 0.0f), glm::vec4(-0.0f, 1e-40f, -1e30f, 0.0f),
                             glm::vec4(0.0f)};
  for (int k = 0; k < 3; ++k) {
    const glm::vec4& r = regs[size_t(5 + k)];
    EXPECT_EQ(std::memcmp(&r, &want[k], sizeof r), 0) << k << ": " << r.x << " " << r.y << " " << r.z << " " << r.w;
  }
}

// The instructions one at a time through their ops' functions, each output clamped as the contract
// says (a lane at a time) unless the op copies: what run() must give, fused steps or not.
std::vector<glm::vec4> run_one_by_one(const std::vector<glm::vec4>& constants, const std::vector<ShaderInstruction>& code,
                                      int registers) {
  std::vector<glm::vec4> regs(size_t(registers), glm::vec4(0.0f));
  std::copy(constants.begin(), constants.end(), regs.begin());
  const ShaderGlobals g;
  for (const ShaderInstruction& ins : code) {
    const ShaderOpInfo info = shader_op_info(ins.op);
    glm::vec4 out = info.run(ShaderOpContext{ins, regs.data(), g, nullptr, 0});
    if (!info.copies)
      for (int k = 0; k < 4; ++k) out[k] = std::isfinite(out[k]) ? std::clamp(out[k], -1e30f, 1e30f) : 0.0f;
    regs[size_t(ins.out)] = out;
  }
  return regs;
}

TEST(ShaderProgramRun, MovesAndSeparateCombineStepsAgreeWithTheOpsOneByOne) {
  std::mt19937 rng(33);
  auto below = [&](int n) { return int(rng() % uint32_t(n)); };
  const float special[] = {-0.0f, 0.0f, 1e-40f, -1e30f, 1e30f, 0.5f, -3.25f, 7.0f};
  int fused = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<glm::vec4> constants(6);
    for (glm::vec4& c : constants)
      for (int k = 0; k < 4; ++k)
        c[k] = below(3) == 0 ? special[below(8)] : std::uniform_real_distribution<float>(-10.0f, 10.0f)(rng);
    const int first = int(constants.size());
    int next = first;  // the next new register
    std::vector<ShaderInstruction> code;
    // A register to read (any written) and one to write (usually new, sometimes one written before).
    auto any = [&] { return below(next); };
    auto out = [&] { return next > first && below(4) == 0 ? first + below(next - first) : next++; };
    for (int piece = 0; piece < 6; ++piece) {
      switch (below(6)) {
        case 0:    // a Separate feeding a Combine: the Combine reads the three channels in some order
        case 1: {  // the same with the channels reading different registers, some reading the run's own
          int ch[3];
          const int source = any();
          for (int k = 0; k < 3; ++k) {
            const int src = below(2) == 0 ? source : any();
            ch[k] = out();
            code.push_back(instruction(ShaderOpcode::Channel, below(4), ch[k], {src}));
          }
          std::shuffle(ch, ch + 3, rng);
          code.push_back(instruction(ShaderOpcode::Combine, 0, out(), {ch[0], ch[1], ch[2]}));
          break;
        }
        case 2:  // three Channels and a Combine of any registers
          for (int k = 0; k < 3; ++k) code.push_back(instruction(ShaderOpcode::Channel, below(4), out(), {any()}));
          code.push_back(instruction(ShaderOpcode::Combine, 0, out(), {any(), any(), any()}));
          break;
        case 3:  // one or two Channels alone (the next piece may make them a run of four or five)
          for (int k = below(2); k < 2; ++k)
            code.push_back(instruction(ShaderOpcode::Channel, below(4), out(), {any()}));
          break;
        case 4: code.push_back(instruction(ShaderOpcode::Combine, 0, out(), {any(), any(), any()})); break;
        default:
          code.push_back(instruction(ShaderOpcode::Math, below(shader::kMathOpCount), out(), {any(), any(), any()}));
      }
    }
    for (size_t i = 0; i + 3 < code.size(); ++i)
      fused += code[i].op == ShaderOpcode::Channel && code[i + 1].op == ShaderOpcode::Channel &&
               code[i + 2].op == ShaderOpcode::Channel && code[i + 3].op == ShaderOpcode::Combine;
    const ShaderProgram program(constants, code, next, 0);
    std::vector<glm::vec4> regs(size_t(next), glm::vec4(0.0f));
    program.run(ShaderGlobals{}, {}, regs.data());
    const std::vector<glm::vec4> want = run_one_by_one(constants, code, next);
    for (int r = 0; r < next; ++r)
      ASSERT_EQ(std::memcmp(&regs[size_t(r)], &want[size_t(r)], sizeof(glm::vec4)), 0)
          << "trial " << trial << " register " << r << ": " << regs[size_t(r)].x << " " << regs[size_t(r)].y << " "
          << regs[size_t(r)].z << " " << regs[size_t(r)].w << " / " << want[size_t(r)].x << " " << want[size_t(r)].y
          << " " << want[size_t(r)].z << " " << want[size_t(r)].w;
  }
  EXPECT_GT(fused, 400);  // the fused step is what most of these programs run
}

}  // namespace
}  // namespace torrance
