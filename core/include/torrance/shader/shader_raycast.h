// The Raycast node (opcode 113, Blender 5.x), as Cycles 5.3 renders it (svm/raycast.h): one ray
// from Position along Direction (not normalised: distances are in its lengths) up to Length,
// traced through ShaderTracer::raycast against every surface whatever its material, or with
// Only Local against the hit's own object alone.
//   Raycast (113)  in0 Position, in1 Direction, in2.x Length, in3.x the Filter Width of the Bump
//                  whose height reads it at an offset hit (0 at the hit itself); flags & 1: Only
//                  Local. mode 0: (Is Hit, Self Hit, Hit Distance, 0); 1: Hit Position; 2: Hit
//                  Normal (world space, w 0).
// At the hit itself a ray from exactly the hit's position passes by the hit's own triangle; at
// a bump's offset hit it starts past 1.1 Filter Width times the ray differential (Cycles'
// tmin), skipping nothing. Self Hit: the surface met belongs to the hit's object (always, with
// Only Local). Hit Normal: the met surface's smooth normal turned toward the ray's origin. A
// miss (nothing within Length, Length <= 0, a zero Direction, or no scene to trace: a world or
// a light) gives Is Hit 0, Self Hit 0, Hit Distance = Length and zero vectors.
#pragma once

#include "torrance/shader/shader_program.h"

namespace torrance::shader {

constexpr uint8_t kRaycastOnlyLocal = 1;

OpValue raycast_op(const ShaderOpContext& c);

}  // namespace torrance::shader
