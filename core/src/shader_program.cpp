#include "torrance/shader_program.h"

#include "torrance/shader_color.h"
#include "torrance/shader_math.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace torrance {
namespace {

// Inputs each opcode reads (in0 .. in(n-1)) and how many modes it has (1: none).
struct OpcodeShape {
  int inputs;
  int modes;
};

OpcodeShape shape_of(ShaderOpcode op) {
  switch (op) {
    case ShaderOpcode::TexCoordUV: return {0, 1};
    case ShaderOpcode::Image: return {1, 1};
    case ShaderOpcode::Channel: return {1, 4};
    case ShaderOpcode::Combine: return {3, 1};
    case ShaderOpcode::Math: return {3, shader::kMathOpCount};
    case ShaderOpcode::VectorMath: return {4, shader::kVectorMathOpCount};
    case ShaderOpcode::MixColor: return {3, shader::kMixBlendCount};
    case ShaderOpcode::MixFloat: return {3, 1};
    case ShaderOpcode::MixVector: return {3, 1};
    case ShaderOpcode::ColorModel: return {1, 4};
    case ShaderOpcode::Invert: return {2, 1};
    case ShaderOpcode::Gamma: return {2, 1};
    case ShaderOpcode::BrightContrast: return {3, 1};
    case ShaderOpcode::HueSaturation: return {5, 1};
    case ShaderOpcode::Luminance: return {1, 1};
    case ShaderOpcode::Average: return {1, 1};
    case ShaderOpcode::Count: break;
  }
  return {0, 0};
}

constexpr float kMaxValue = 1e30f;  // program values stay finite and well inside float's range

float finite_or_zero(float v) { return std::isfinite(v) ? std::clamp(v, -kMaxValue, kMaxValue) : 0.0f; }
glm::vec4 finite(const glm::vec4& v) {
  return glm::vec4(finite_or_zero(v.x), finite_or_zero(v.y), finite_or_zero(v.z), finite_or_zero(v.w));
}
glm::vec4 color(const Vec3& c, float w = 1.0f) { return glm::vec4(c, w); }
glm::vec4 value(float v) { return glm::vec4(v, 0.0f, 0.0f, 0.0f); }

}  // namespace

ShaderProgram::ShaderProgram(std::vector<glm::vec4> constants, std::vector<ShaderInstruction> code, int registers,
                             size_t num_textures)
    : constants_(std::move(constants)), code_(std::move(code)), registers_(registers) {
  if (registers_ < 1 || registers_ > kMaxRegisters)
    throw std::invalid_argument("a shader program has 1 to " + std::to_string(kMaxRegisters) + " registers, got " +
                                std::to_string(registers_));
  if (int(constants_.size()) > registers_)
    throw std::invalid_argument("a shader program's constants (" + std::to_string(constants_.size()) +
                                ") exceed its registers (" + std::to_string(registers_) + ")");
  for (const glm::vec4& c : constants_)
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) || !std::isfinite(c.w))
      throw std::invalid_argument("a shader program's constants must be finite");
  std::vector<bool> written(size_t(registers_), false);
  for (size_t r = 0; r < constants_.size(); ++r) written[r] = true;
  for (size_t i = 0; i < code_.size(); ++i) {
    const ShaderInstruction& ins = code_[i];
    const std::string where = "shader instruction " + std::to_string(i);
    if (ins.op >= ShaderOpcode::Count) throw std::invalid_argument(where + ": unknown opcode " + std::to_string(int(ins.op)));
    const OpcodeShape s = shape_of(ins.op);
    if (ins.mode >= s.modes)
      throw std::invalid_argument(where + ": mode " + std::to_string(int(ins.mode)) + " out of range [0, " +
                                  std::to_string(s.modes) + ")");
    for (int k = 0; k < s.inputs; ++k) {
      const int r = ins.in[size_t(k)];
      if (r < 0 || r >= registers_ || !written[size_t(r)])
        throw std::invalid_argument(where + ": input " + std::to_string(k) + " reads register " + std::to_string(r) +
                                    ", which is not written before it");
    }
    if (ins.out < int(constants_.size()) || ins.out >= registers_)
      throw std::invalid_argument(where + ": output register " + std::to_string(ins.out) + " outside [" +
                                  std::to_string(constants_.size()) + ", " + std::to_string(registers_) + ")");
    if (ins.op == ShaderOpcode::Image && (ins.texture < 0 || size_t(ins.texture) >= num_textures))
      throw std::invalid_argument(where + ": texture " + std::to_string(ins.texture) + " but the scene has " +
                                  std::to_string(num_textures) + " textures");
    written[size_t(ins.out)] = true;
  }
  written_ = std::move(written);
}

void ShaderProgram::run(const ShaderGlobals& g, const std::vector<std::shared_ptr<const Texture>>& textures,
                        glm::vec4* regs) const {
  for (size_t r = 0; r < constants_.size(); ++r) regs[r] = constants_[r];
  for (const ShaderInstruction& ins : code_) {
    auto in = [&](int k) -> const glm::vec4& { return regs[ins.in[size_t(k)]]; };
    auto rgb = [&](int k) { return Vec3(in(k)); };
    glm::vec4 out(0.0f);
    switch (ins.op) {
      case ShaderOpcode::TexCoordUV: out = glm::vec4(g.uv, 0.0f, 0.0f); break;
      case ShaderOpcode::Image: out = textures[size_t(ins.texture)]->lookup(Vec2(in(0)), g.footprint); break;
      case ShaderOpcode::Channel: out = value(in(0)[ins.mode]); break;
      case ShaderOpcode::Combine: out = glm::vec4(in(0).x, in(1).x, in(2).x, 1.0f); break;
      case ShaderOpcode::Math: {
        float v = shader::math(shader::MathOp(ins.mode), in(0).x, in(1).x, in(2).x);
        if (ins.flags & 1) v = std::clamp(v, 0.0f, 1.0f);
        out = value(v);
        break;
      }
      case ShaderOpcode::VectorMath: {
        Vec3 vector(0.0f);
        float scalar = 0.0f;
        shader::vector_math(shader::VectorMathOp(ins.mode), rgb(0), rgb(1), rgb(2), in(3).x, &vector, &scalar);
        out = (ins.flags & 1) ? value(scalar) : glm::vec4(vector, 0.0f);
        break;
      }
      case ShaderOpcode::MixColor:
        out = color(shader::mix_color(shader::MixBlend(ins.mode), shader::mix_factor(in(0).x, ins.flags & 2), rgb(1),
                                      rgb(2), ins.flags & 1));
        break;
      case ShaderOpcode::MixFloat:
        out = value(shader::mix_float(shader::mix_factor(in(0).x, ins.flags & 2), in(1).x, in(2).x));
        break;
      case ShaderOpcode::MixVector: {
        Vec3 factor = (ins.flags & 4) ? rgb(0) : Vec3(in(0).x);
        if (ins.flags & 2) factor = glm::clamp(factor, Vec3(0.0f), Vec3(1.0f));
        out = glm::vec4(shader::mix_vector(factor, rgb(1), rgb(2)), 0.0f);
        break;
      }
      case ShaderOpcode::ColorModel: {
        const Vec3 c = rgb(0);
        const Vec3 converted = ins.mode == 0   ? shader::rgb_to_hsv(c)
                               : ins.mode == 1 ? shader::hsv_to_rgb(c)
                               : ins.mode == 2 ? shader::rgb_to_hsl(c)
                                               : shader::hsl_to_rgb(c);
        out = color(converted);
        break;
      }
      case ShaderOpcode::Invert: out = color(shader::invert(in(0).x, rgb(1))); break;
      case ShaderOpcode::Gamma: out = color(shader::gamma(rgb(0), in(1).x)); break;
      case ShaderOpcode::BrightContrast: out = color(shader::bright_contrast(rgb(0), in(1).x, in(2).x)); break;
      case ShaderOpcode::HueSaturation:
        out = color(shader::hue_saturation_value(in(0).x, in(1).x, in(2).x, in(3).x, rgb(4)));
        break;
      case ShaderOpcode::Luminance: out = value(shader::rgb_to_bw(rgb(0))); break;
      case ShaderOpcode::Average: out = value((in(0).x + in(0).y + in(0).z) / 3.0f); break;
      case ShaderOpcode::Count: break;
    }
    regs[ins.out] = finite(out);
  }
}

}  // namespace torrance
