#include "torrance/lights/emission_shader.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace torrance {

EmissionShader::EmissionShader(ShaderProgram program, int radiance_register,
                               std::vector<std::shared_ptr<const Texture>> textures)
    : program_(std::move(program)), radiance_register_(radiance_register), textures_(std::move(textures)) {
  if (!program_.written(radiance_register_))
    throw std::invalid_argument("the radiance register " + std::to_string(radiance_register_) +
                                " is not written by its program");
  reads_path_ = program_.reads(ShaderOpcode::LightPath);
}

ShaderGlobals EmissionShader::background_globals(const Vec3& dir, const PathState& state) {
  ShaderGlobals g;
  g.position = dir;
  g.normal = g.true_normal = g.incoming = -dir;
  g.path = state;
  g.path.ray_length = 0.0f;  // as Cycles' background
  return g;
}

ShaderGlobals EmissionShader::light_globals(const Vec3& position, const Vec3& normal, const Vec3& incoming,
                                            float distance, const PathState& state) {
  ShaderGlobals g;
  g.position = position;
  g.normal = g.true_normal = normal;
  g.incoming = incoming;
  g.path = state;
  g.path.ray_length = std::isfinite(distance) ? distance : 1e30f;
  return g;
}

Vec3 EmissionShader::radiance(const ShaderGlobals& g) const {
  glm::vec4 regs[ShaderProgram::kMaxRegisters];
  program_.run(g, textures_, regs);
  // Negative radiance takes light away, as Cycles renders it (a world or lamp of negative
  // strength); only what is not finite is dropped.
  Vec3 radiance(regs[radiance_register_]);
  for (int c = 0; c < 3; ++c)
    if (!std::isfinite(radiance[c])) radiance[c] = 0.0f;
  return radiance;
}

}  // namespace torrance
