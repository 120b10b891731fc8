// Values of Blender's data passes at the camera path's first surface that the path tracer
// computes from the material and the camera (the rest come straight from the hit).
#pragma once

#include "integrator/path_tracer.h"

namespace torrance {

// The Mist pass's value of a surface at `position` (Cycles' film_write_data_passes): 1 - mist,
// mist = ((distance - start) / depth) clamped to [0, 1], raised to the falloff; the distance
// from the camera's position (orthographic: along its axis).
float mist_clearance(const PathContext& ctx, const Vec3& position);

// The Glossy Color pass of a material: Cycles 3.4's Glossy Color of a Principled BSDF
// (svm/closure.h: the weight of its specular closure, present with some Specular or Metallic,
// 1 - the transmitting share, and of its clearcoat, 1) plus its Transmission Color (the glass
// closures' weight: the transmitting share; the Glass BSDF's colour), since Torrance files the
// light through glass with the glossy passes (it has no Transmission passes).
Vec3 glossy_color(const Material& m);

// The Diffuse Color pass (DiffCol): the diffuse lobe's weight, which glass takes away (Cycles'
// TransCol); kGlass: some material of the scene transmits.
template <bool kGlass>
Vec3 diffuse_color(const Material& m) {
  if (!kGlass) return m.base_color * (1.0f - m.metallic);
  return m.base_color * (m.glass_node ? 0.0f : (1.0f - m.metallic) * (1.0f - m.transmission));
}

}  // namespace torrance
