// The Bevel node (opcode 103), as Cycles 3.4 renders it (svm/bevel.h): the smooth normals of the
// hit's own object found by local rays (ShaderTracer::local_hits) through a disk of the Radius
// about the hit, blended by weight.
//   Bevel (103)  in0.x Radius, in1 the node's Normal input, in2.x Samples; flags & 1: the Normal
//                input is linked (then the result is normalize(Normal + bevelled - the shading
//                normal), as Cycles keeps a bumped normal's detail). Out: the normal, facing
//                the viewer, world space (w 0).
// Each sample picks an axis of the frame about the true normal (the normal with probability
// 1/2, either tangent 1/4), a point on the disk across it at a radius drawn from the cubic
// profile 10 (R - r)^3 / (pi R^5) (Cycles' "cubic BSSRDF"), and traces from height h =
// sqrt(R^2 - r^2) above the disk down through 2 h against the object alone, keeping at most four
// hits (a uniform choice among all). A hit's smooth normal is weighted by the power heuristic of
// the three axes' pdfs (each axis's pick probability times |axis . hit's true normal|), by the
// share of hits it stands for (all / 4 when more were found), and by the profile at the hit's
// true distance over the profile at the sampled radius. The sum, normalised, facing the viewer;
// the shading normal when the sum is zero, with no tracer, no object, a Radius or Samples below
// the least, or on a path that has taken a blurry bounce: Cycles bevels only while min_ray_pdf
// >= 8, which every diffuse and rough bounce brings below (PathState approximates it).
#pragma once

#include "torrance/shader/shader_program.h"

namespace torrance::shader {

OpValue bevel_op(const ShaderOpContext& c);

// Cycles' radius profile: its density at r for radius R (0 from R on), and the radius whose
// cumulative share is xi (Newton's method on the quintic).
float bevel_profile(float radius, float r);
float bevel_sample_radius(float radius, float xi);

// The bevelled normal at the hit (facing the viewer), before any Normal input is blended in.
Vec3 bevel_normal(const ShaderGlobals& g, float radius, int samples);

}  // namespace torrance::shader
