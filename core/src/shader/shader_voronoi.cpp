#include "torrance/shader/shader_voronoi.h"

#include "shader/voronoi_search.h"

namespace torrance::shader {

namespace {

using namespace voronoi_search;

// Cycles 3.4's node: one octave, positions divided by Scale (0 when Scale is 0).
VoronoiOutputs evaluate(const VoronoiSettings& settings, const VoronoiInputs& in, bool color) {
  const Params q{clamp_to(in.smoothness / 2.0f, 0.0f, 0.5f), in.exponent, clamp_to(in.randomness, 0.0f, 1.0f),
                 settings.metric, color, false, 8.0f};
  return for_dimensions(settings.dimensions, [&](auto dimensions) {
    constexpr int D = decltype(dimensions)::value;
    Found<D> f = search<D>(coordinate<D>(in), settings.feature, q);
    f.position = in.scale != 0.0f ? f.position / in.scale : VecN<D>(0.0f);
    return outputs_of<D>(f);
  });
}

}  // namespace

VoronoiOutputs voronoi(const VoronoiSettings& settings, const VoronoiInputs& in) {
  return evaluate(settings, in, true);
}

OpValue voronoi_op(const ShaderOpContext& c) {
  if (c.ins.flags > kVoronoiRadius) return glm::vec4(0.0f);
  return op_outputs(c, evaluate);
}

}  // namespace torrance::shader
