#include "torrance/background_shader.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace torrance {

BackgroundShader::BackgroundShader(ShaderProgram program, int radiance_register,
                                   std::vector<std::shared_ptr<const Texture>> textures)
    : program_(std::move(program)), radiance_register_(radiance_register), textures_(std::move(textures)) {
  if (!program_.written(radiance_register_))
    throw std::invalid_argument("the world's radiance register " + std::to_string(radiance_register_) +
                                " is not written by its program");
  reads_path_ = program_.reads(ShaderOpcode::LightPath);
}

ShaderGlobals BackgroundShader::globals(const Vec3& dir, const PathState& state) {
  ShaderGlobals g;
  g.position = dir;
  g.normal = g.true_normal = g.incoming = -dir;
  g.path = state;
  g.path.ray_length = 0.0f;  // as Cycles' background
  return g;
}

Vec3 BackgroundShader::radiance(const Vec3& dir, const PathState& state) const {
  glm::vec4 regs[ShaderProgram::kMaxRegisters];
  program_.run(globals(dir, state), textures_, regs);
  return glm::max(Vec3(regs[radiance_register_]), Vec3(0.0f));
}

}  // namespace torrance
