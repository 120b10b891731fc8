// Blender's Voronoi Texture node (ShaderNodeTexVoronoi) as Cycles 3.4 computes it on the CPU: the
// same feature points (one per unit cell, placed by the Cycles hashes of shader_hash.h), searched
// in the same order with the same float operations, so cells, distances, colours and positions
// agree with Cycles' to the last bit or two.
//
// What the node computes, at the coordinate p = Vector * Scale (and w = W * Scale):
//   - each integer cell c holds one point, c + hash(c) * Randomness (Randomness clamped to
//     [0, 1]); the search visits the cells around p's cell (3 per axis, 5 for Smooth F1) with x
//     varying fastest, a point replacing the best so far only when strictly closer, the best
//     distance starting at 8 (so a metric giving distances >= 8 everywhere, e.g. Minkowski with a
//     tiny exponent, leaves the defaults: distance 8, the own cell's colour, the cell corner);
//   - F1: the closest point; F2: the second closest (ties keep the earlier cell); Smooth F1: the
//     distance, colour and position blended over all 5^n cells by a smooth minimum of width
//     Smoothness / 2 (clamped to [0, 0.5]); Distance to Edge: the distance to the closest
//     Voronoi edge (Euclidean whatever the metric); N-Sphere Radius: half the distance between
//     the closest point and the point closest to it (Euclidean);
//   - metrics: Euclidean, Manhattan, Chebychev, Minkowski (Exponent); 1D is always |a - b|;
//   - Color: the chosen cell's hash as an RGB colour; Position (and W): the chosen point divided
//     by Scale (0 when Scale is 0); outputs a feature does not compute are 0.
// Dimensions: 1D reads W only, 2D Vector's x and y, 3D Vector, 4D Vector and W.
//
// Blender 4.0+'s node (Cycles 4.x, voronoi4 and the VoronoiV4 op below) adds fractal Voronoi:
//   - octaves i = 0 .. ceil(Detail) (Detail clamped to [0, 15]) at the coordinate times
//     Lacunarity^i, weighted Roughness^i (Roughness clamped to [0, 1]); F1, F2 and Smooth F1 sum
//     distances and colours and blend positions (lerp by the weight), the last octave by Detail's
//     fraction; Distance to Edge keeps a blended running minimum of the octaves' distances (each
//     divided by its scale); Detail or Roughness 0: the first octave alone;
//   - Normalize divides the distance by the weights' sum times the largest distance a feature
//     can have (the metric's length of (0.5 + 0.5 Randomness) on every axis, twice for F2; for
//     Distance to Edge 0.5 + 0.5 Randomness scaled like the distances), the colour by the sum;
//   - searches start from FLT_MAX instead of 8, Smooth F1 takes the first cell as it is (then
//     blends), Smoothness 0 is F1, and positions are multiplied by 1 / scale (4.x's divisions).
// Cycles 5.0 hashes the cells of 2 to 4 dimensions as integers (PCG, shader_hash.h: faster, a
// new pattern; 1D keeps the float hash): VoronoiFractal::integer_hash, measured in 5.3. (5.x also
// picks F1's and N-Sphere Radius's closest point by a cheaper monotone measure, the squared
// Euclidean distance or the Minkowski sum before its root, then measures it: the same point but
// at ties, not modelled.)
// N-Sphere Radius has no octaves. (4.2.0's kernel read Lacunarity from Smoothness's slot; the
// 4.2 LTS Blender the tests run, 4.2.23, reads Lacunarity, as this does.)
// Cycles 3.4's node is shader_voronoi.cpp, 4.x's shader_voronoi4.cpp, over the searches both
// share (voronoi_search.h); 4.x's twin is python_addon/torrance/shader_graph/voronoi4.py.
//
// The Python twin (python_addon/torrance/shader_graph/voronoi.py) is the add-on's constant folder;
// both are checked against core/tests/data/shader_voronoi_cases.json, which Blender 3.4.1's Cycles
// rendered.
#pragma once

#include "torrance/util/math.h"

#include <cstdint>

namespace torrance {
struct ShaderOpContext;
struct OpValue;
}

namespace torrance::shader {

// Blender's identifiers, in Blender's (and Cycles') order.
enum class VoronoiFeature : uint8_t { F1, F2, SmoothF1, DistanceToEdge, NSphereRadius };
constexpr int kVoronoiFeatureCount = 5;
enum class VoronoiMetric : uint8_t { Euclidean, Manhattan, Chebychev, Minkowski };
constexpr int kVoronoiMetricCount = 4;

struct VoronoiSettings {
  int dimensions = 3;  // 1 to 4
  VoronoiFeature feature = VoronoiFeature::F1;
  VoronoiMetric metric = VoronoiMetric::Euclidean;
};

// The node's sockets.
struct VoronoiInputs {
  Vec3 vector{0.0f};
  float w = 0.0f;
  float scale = 5.0f;
  float smoothness = 1.0f;
  float exponent = 0.5f;
  float randomness = 1.0f;
};
struct VoronoiOutputs {
  float distance = 0.0f;
  Vec3 color{0.0f};
  Vec3 position{0.0f};
  float w = 0.0f;
  float radius = 0.0f;
};

// Blender 4.x's fractal sockets and setting, and which hash the Cycles uses.
struct VoronoiFractal {
  float detail = 0.0f;
  float roughness = 0.5f;
  float lacunarity = 2.0f;
  bool normalize = false;
  bool integer_hash = false;  // Cycles 5.0+: cells of 2 to 4 dimensions hashed as integers (PCG)
};

// All the node's outputs (any inputs; non-finite ones give what Cycles' float arithmetic does).
VoronoiOutputs voronoi(const VoronoiSettings& settings, const VoronoiInputs& in);
// The same as Cycles 4.x computes them (Blender 4.0+'s node).
VoronoiOutputs voronoi4(const VoronoiSettings& settings, const VoronoiInputs& in, const VoronoiFractal& fractal);

// ---- the shader program's op (ShaderOpcode::Voronoi) ----
//
// mode = (dimensions - 1) + 4 * feature + 20 * metric (kVoronoiModes modes);
// inputs: in0 Vector (xyz), in1 W, in2 Scale, in3 Smoothness, in4 Exponent, in5 Randomness (x);
// flags picks what the instruction writes (the add-on emits one per output group it uses):
//   0 (kVoronoiColorDistance): (Color.r, Color.g, Color.b, Distance): a colour, its w the
//                              Distance (which a Channel of mode 3 takes out);
//   1 (kVoronoiPositionW):     (Position.x, .y, .z, W): a vector, its w the W output;
//   2 (kVoronoiRadius):        (Radius, 0, 0, 0);
//   anything else:             (0, 0, 0, 0).
constexpr int kVoronoiModes = 4 * kVoronoiFeatureCount * kVoronoiMetricCount;
constexpr uint8_t kVoronoiColorDistance = 0, kVoronoiPositionW = 1, kVoronoiRadius = 2;

constexpr int voronoi_mode(const VoronoiSettings& s) {
  return (s.dimensions - 1) + 4 * int(s.feature) + 4 * kVoronoiFeatureCount * int(s.metric);
}
constexpr VoronoiSettings voronoi_settings(int mode) {
  return {mode % 4 + 1, VoronoiFeature(mode / 4 % kVoronoiFeatureCount),
          VoronoiMetric(mode / (4 * kVoronoiFeatureCount))};
}

OpValue voronoi_op(const ShaderOpContext& c);

// ShaderOpcode::VoronoiV4 (Blender 4.0+'s node, voronoi4): modes and output groups as Voronoi's
// (flags & 3), flags & 4 (kVoronoiNormalize): Normalize, flags & 8 (kVoronoiIntegerHash): Cycles
// 5.0+'s cells; inputs Voronoi's six, then in6 Detail, in7 Roughness, in8 Lacunarity.
constexpr uint8_t kVoronoiNormalize = 4, kVoronoiIntegerHash = 8;
OpValue voronoi4_op(const ShaderOpContext& c);

}  // namespace torrance::shader
