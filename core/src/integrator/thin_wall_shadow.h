// The straight pass of a smooth thin wall (Principled Thin Wall, bsdfs/thin_wall_v2.h) as the rays
// other than the camera's see it. Cycles 5.x makes a thin wall's transmission lobe a Transparent
// closure of the same weight when that lobe is smooth and the ray is not a camera ray
// (bsdf_thin_glass_transmission_setup: the sheet does not bend light), so shadow rays pass the
// sheet carrying the slab's transmittance at their cosine times the transmission's layer weights,
// and indirect rays go on through it as through alpha (path_tracer.cpp). A rough sheet, or one seen
// by the camera, keeps its lobe. Thin Wall exists in PRINCIPLED_V2 alone (Blender 5.x): its
// materials are built with that model here.
#pragma once

#include "torrance/scene/scene.h"

namespace torrance {

// Whether material `id` (or a closure of its mixture) is a thin wall: only then can a ray pass
// it straight (straight_through may still find its sheet rough at a hit).
bool may_pass_straight(const Scene& scene, uint32_t id);

// What a ray along `dir` carries through the hit's smooth thin walls (seen_by: the ray's state,
// for the material's programs), per channel: 0 where none is smooth. The material's alpha and
// Transparent closures are not included (Scene::opacity's; the pass is under its opaque share).
Vec3 straight_through(const Scene& scene, const SurfaceHit& hit, const Vec3& dir, const PathState& seen_by);

}  // namespace torrance
