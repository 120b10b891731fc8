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
//   LightPath (106)   Light Path: (value, 0, 0, 0) of the path's state (PathState), mode 0 Is
//                     Camera Ray, 1 Is Shadow Ray, 2 Is Diffuse, 3 Is Glossy, 4 Is Singular,
//                     5 Is Reflection, 6 Is Transmission Ray, 7 Ray Length, 8 Ray Depth,
//                     9 Diffuse, 10 Glossy, 11 Transparent, 12 Transmission, 13 Portal Depth
//   LightFalloff (109) Light Falloff (svm/light_path.h): in0.x Strength, in1.x Smooth; mode 0
//                     Quadratic (Strength), 1 Linear (x ray length), 2 Constant (x its square);
//                     then, for Smooth > 0, x l^2 / (Smooth + l^2) (l the ray length, PathState)
//   Wireframe (110)   the Wireframe node (svm/wireframe.h): 1 where the hit lies within in0.x Size / 2
//                     of an edge of its triangle (ShaderGlobals::corners, world space), else 0;
//                     mode 0: Size in metres, 1 (Pixel Size): in pixels, a pixel the mean length
//                     of dP/dx and dP/dy projected onto the plane facing the viewer
//   AmbientOcclusion (102) the Ambient Occlusion node (svm/ao.h): the share of in3.x Samples rays,
//                     cosine-distributed about the normal in2 (reversed with flags & 1: Inside),
//                     that reach in1.x Distance unoccluded (ShaderGlobals::tracer; 1 without
//                     one, or a Distance or Samples below 1, as Cycles' for no object); with
//                     flags & 2 (Only Local) only the hit's own object occludes (the tracer's
//                     local query: none occludes without an object); mode 0 Color: in0 times
//                     it, 1 AO: it
//   Tangent (101)     the Tangent node (svm/tex_coord.h): mode 0-2 Radial about X, Y, Z of in0
//                     (Generated, w 0 where the mesh lacks it: then the position), 3 UV Map (the
//                     hit's UV tangent, ShaderGlobals::tangent, taken back to object space);
//                     in1-in4 the object (shader_vector.h's ObjectTransform), in5 the shading
//                     normal. Out: the tangent through the object's normal transform, made
//                     perpendicular to the normal (0 without UVs)
//   CameraTransform (107) the hit's position through the 4x4 matrix whose rows are in0-in3 (the
//                     add-on's per-render constants: world to camera, or world to the camera's
//                     NDC): mode 0 normalize(M p) (Camera Data > View Vector), 1 (M p).z (View
//                     Z Depth), 2 |M p| (View Distance), 3 M p (Texture Coordinate > Camera),
//                     4 ((M p).x / w, (M p).y / w, 0), w = row 3 . (p, 1) (Window)
// A node's unlinked Normal input is the shading normal (the add-on links Geometry > Normal).
#pragma once

#include "torrance/shader/shader_program.h"

namespace torrance::shader {

OpValue geometry_op(const ShaderOpContext& c);
OpValue reflection_op(const ShaderOpContext& c);
OpValue fresnel_op(const ShaderOpContext& c);
OpValue layer_weight_op(const ShaderOpContext& c);
OpValue attribute_op(const ShaderOpContext& c);
constexpr int kLightPathModes = 14;
OpValue light_path_op(const ShaderOpContext& c);
constexpr int kLightFalloffModes = 3;
OpValue light_falloff_op(const ShaderOpContext& c);
OpValue wireframe_op(const ShaderOpContext& c);
constexpr uint8_t kAmbientOcclusionInside = 1, kAmbientOcclusionOnlyLocal = 2;  // its flags
OpValue ambient_occlusion_op(const ShaderOpContext& c);
constexpr int kTangentModes = 4;
OpValue tangent_op(const ShaderOpContext& c);
constexpr int kCameraTransformModes = 5;
OpValue camera_transform_op(const ShaderOpContext& c);

// Cycles' Layer Weight, from the cosine between the view direction and the normal.
float layer_weight_fresnel(float blend, float cos_view, bool backfacing);
float layer_weight_facing(float blend, float cos_view);

}  // namespace torrance::shader
