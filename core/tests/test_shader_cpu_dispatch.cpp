// The procedural textures' AVX2 build (cpu_dispatch.h) against the baseline build: the same bits
// for every op it covers (Voronoi of both Blender versions, Noise, Musgrave), over random inputs.
#include <gtest/gtest.h>

#include "../src/shader/cpu_dispatch.h"
#include "torrance/shader/shader_program.h"
#include "torrance/shader/shader_voronoi.h"

#include <cstring>
#include <random>
#include <vector>

using namespace torrance;

namespace {

// The op's output with the AVX2 build on or off.
glm::vec4 run(const ShaderInstruction& ins, const std::vector<glm::vec4>& inputs, bool avx2) {
  const bool was = cpu_dispatch::use_avx2();
  cpu_dispatch::use_avx2() = avx2;
  std::vector<glm::vec4> regs(inputs.size() + 1);
  const ShaderProgram program(inputs, {ins}, int(inputs.size() + 1), 0);
  program.run(ShaderGlobals{}, {}, regs.data());
  cpu_dispatch::use_avx2() = was;
  return regs.back();
}

bool same_bits(const glm::vec4& a, const glm::vec4& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST(CpuDispatch, Avx2BuildGivesTheBaselineBits) {
  if (!cpu_dispatch::use_avx2()) GTEST_SKIP() << "this CPU (or build) runs the baseline build only";
  std::mt19937 rng(33);
  std::uniform_real_distribution<float> coord(-40.0f, 40.0f), unit(0.0f, 1.0f);
  struct Case {
    ShaderOpcode op;
    int modes, flags, inputs;
  };
  const Case cases[] = {{ShaderOpcode::Voronoi, shader::kVoronoiModes, 3, 6},
                        {ShaderOpcode::VoronoiV4, shader::kVoronoiModes, 3, 9},
                        {ShaderOpcode::Noise, 4, 2, 6},
                        {ShaderOpcode::Musgrave, 20, 1, 8}};
  int compared = 0;
  for (const Case& c : cases) {
    const int modes = std::min(c.modes, shader_op_info(c.op).modes);
    for (int mode = 0; mode < modes; ++mode)
      for (int flags = 0; flags < c.flags; ++flags)
        for (int trial = 0; trial < 4; ++trial) {
          std::vector<glm::vec4> inputs;
          inputs.push_back(glm::vec4(coord(rng), coord(rng), coord(rng), coord(rng)));
          for (int k = 1; k < c.inputs; ++k) inputs.push_back(glm::vec4(0.2f + 4.0f * unit(rng), 0.0f, 0.0f, 0.0f));
          ShaderInstruction ins;
          ins.op = c.op;
          ins.mode = uint8_t(mode);
          ins.flags = uint8_t(flags);
          ins.out = int16_t(inputs.size());
          for (int k = 0; k < c.inputs; ++k) ins.in[size_t(k)] = int16_t(k);
          const glm::vec4 fast = run(ins, inputs, true), baseline = run(ins, inputs, false);
          EXPECT_TRUE(same_bits(fast, baseline)) << "op " << int(c.op) << " mode " << mode << " flags " << flags;
          ++compared;
        }
  }
  EXPECT_GT(compared, 500);
}
