// The shader graph's geometry family (opcodes 96-127): what the nodes that read the hit compute,
// as Cycles 3.4 (svm/geometry.h, tex_coord.h, fresnel.h):
//   Geometry (96)     mode 0 Position, 1 Normal, 2 True Normal, 3 Incoming (xyz), 4 Backfacing (x)
//   Reflection (97)   Texture Coordinate > Reflection: the view direction mirrored about the
//                     normal, world space
//   Fresnel (98)      in0.x IOR, in1 the normal: the dielectric reflectance toward the viewer
//                     (IOR inverted on a back face)
//   LayerWeight (99)  in0.x Blend, in1 the normal; mode 0 Fresnel, 1 Facing
//   Attribute (100)   the mesh attribute named by the resource (Scene::set_mesh_attributes),
//                     interpolated over the hit triangle: xyz, w 1 (all 0 where the mesh lacks
//                     it, as Cycles reads a missing attribute)
// A node's unlinked Normal input is the shading normal (the add-on links Geometry > Normal).
#pragma once

#include "torrance/shader_program.h"

namespace torrance::shader {

glm::vec4 geometry_op(const ShaderOpContext& c);
glm::vec4 reflection_op(const ShaderOpContext& c);
glm::vec4 fresnel_op(const ShaderOpContext& c);
glm::vec4 layer_weight_op(const ShaderOpContext& c);
glm::vec4 attribute_op(const ShaderOpContext& c);

// Cycles' Layer Weight, from the cosine between the view direction and the normal.
float layer_weight_fresnel(float blend, float cos_view, bool backfacing);
float layer_weight_facing(float blend, float cos_view);

}  // namespace torrance::shader
