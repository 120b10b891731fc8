// The world's node graph as a shader program: Cycles' background shader. The add-on compiles the
// World Output's Surface (Background and Emission closures, Mix and Add Shader of them) into one
// program whose radiance register holds the sum of the closures' Color x Strength, weighted.
//
// The program sees a direction as Cycles' shader_setup_from_background sets it up: the position
// is the direction itself (Texture Coordinate > Generated and Object, an Environment Texture's
// unlinked Vector), the normals and the incoming direction are its opposite, UVs are 0, no mesh
// attribute or object. The path state is the escaping ray's (Light Path: Is Camera Ray, ...).
#pragma once

#include "torrance/shader_program.h"

#include <memory>
#include <vector>

namespace torrance {

class BackgroundShader {
 public:
  // Throws std::invalid_argument unless radiance_register is written by the program.
  BackgroundShader(ShaderProgram program, int radiance_register,
                   std::vector<std::shared_ptr<const Texture>> textures);

  // The radiance a ray of state `state` travelling along unit direction dir receives from the
  // world: the program's radiance register, negative parts 0.
  Vec3 radiance(const Vec3& dir, const PathState& state) const;
  // Whether the program reads the path's state (then the path tracer keeps it up to date).
  bool reads_path() const { return reads_path_; }

  static ShaderGlobals globals(const Vec3& dir, const PathState& state);

 private:
  ShaderProgram program_;
  int radiance_register_;
  std::vector<std::shared_ptr<const Texture>> textures_;
  bool reads_path_ = false;
};

}  // namespace torrance
