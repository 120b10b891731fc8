// A heterogeneous medium: a volume whose coefficients vary through it (Cycles' volume shader
// with inputs fed by textures, maths, ramps ...). A shader program, run at a point inside (its
// position the point's, its normal and incoming direction the ray's reversed, as Cycles' volume
// ShaderData), computes the absorption and scattering coefficients and the emitted radiance per
// metre in three colour registers; the Henyey-Greenstein anisotropy is constant. `majorant`
// bounds max_component(sigma_a + sigma_s) over the medium (Scene computes it from a grid of the
// program's values over the bounds): the free-flight tracking's rate of tentative collisions.
#pragma once

#include "torrance/media/phase_function.h"

#include <cstdint>

namespace torrance {

struct VaryingMedium {
  uint32_t program = 0;  // from Scene::add_shader_program
  int16_t sigma_a = -1, sigma_s = -1, emission = -1;  // colour registers (xyz); -1: zero
  float anisotropy = 0.0f;
  PhaseKind phase = PhaseKind::HenyeyGreenstein;  // its phase function, constant (as HomogeneousMedium's)
  float phase_a = 0.0f, phase_b = 0.0f;
  Vec3 bounds_min{0.0f}, bounds_max{0.0f};  // world box the medium's meshes lie in
  float majorant = 0.0f;  // per metre, > 0 (set by Scene)
};

}  // namespace torrance
