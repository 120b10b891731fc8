// The node graph of a world or a light as a shader program: Cycles' background and light
// shaders. The add-on compiles the World / Light Output's Surface (Background and Emission
// closures, Mix and Add Shader of them; python_addon/torrance/shader_graph/emission_tree.py)
// into one program whose radiance register holds the sum of the closures' Color x Strength,
// weighted.
//
// A world's program sees a direction as Cycles' shader_setup_from_background sets it up: the
// position is the direction itself (Texture Coordinate > Generated and Object, an Environment
// Texture's unlinked Vector), the normals and the incoming direction are its opposite, UVs are
// 0, no mesh attribute or object. A light's sees the point on the light (light_globals), its
// ray length the distance to the receiver (Light Falloff). The path state is the ray's (Light
// Path: Is Camera Ray, ...).
#pragma once

#include "torrance/shader/shader_program.h"

#include <memory>
#include <vector>

namespace torrance {

class EmissionShader {
 public:
  // Throws std::invalid_argument unless radiance_register is written by the program.
  EmissionShader(ShaderProgram program, int radiance_register, std::vector<std::shared_ptr<const Texture>> textures);

  // The program's radiance register at g (negative parts take light away), parts not finite 0.
  Vec3 radiance(const ShaderGlobals& g) const;
  // A world's radiance that a ray of state `state` travelling along unit direction dir receives.
  Vec3 background(const Vec3& dir, const PathState& state) const { return radiance(background_globals(dir, state)); }
  // Whether the program reads the path's state (then the path tracer keeps it up to date).
  bool reads_path() const { return reads_path_; }

  static ShaderGlobals background_globals(const Vec3& dir, const PathState& state);
  // A light's point `position` (normal `normal`) seen from `distance` away along -incoming.
  static ShaderGlobals light_globals(const Vec3& position, const Vec3& normal, const Vec3& incoming, float distance,
                                     const PathState& state);

 private:
  ShaderProgram program_;
  int radiance_register_;
  std::vector<std::shared_ptr<const Texture>> textures_;
  bool reads_path_ = false;
};

}  // namespace torrance
