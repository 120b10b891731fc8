// Blender 4.x's Voronoi Texture as Cycles 4.x computes it (shader_voronoi.h): the octaves of
// fractal Voronoi over the searches Cycles 3.4's node shares (voronoi_search.h).
#include "torrance/shader/shader_voronoi.h"

#include "shader/voronoi_search.h"

namespace torrance::shader {

namespace {

using namespace voronoi_search;

template <typename T>
T lerp(const T& a, const T& b, float t) {
  return a + t * (b - a);
}

// Cycles' reduce_add: four components in pairs (SSE3's hadd), fewer left to right.
template <int D>
float reduce_add(const VecN<D>& v) {
  if constexpr (D == 4) return (v.x + v.y) + (v.z + v.w);
  float sum = v[0];
  for (int k = 1; k < D; ++k) sum += v[k];
  return sum;
}

// The metric's length of v (Cycles' voronoi_distance from 0 to v).
template <int D>
float metric_length(const VecN<D>& v, VoronoiMetric metric, float exponent) {
  const VecN<D> a = glm::abs(v);
  switch (metric) {
    case VoronoiMetric::Euclidean: return length<D>(v);
    case VoronoiMetric::Manhattan: return reduce_add<D>(a);
    case VoronoiMetric::Chebychev: {
      float most = a[D - 1];
      for (int k = D - 2; k >= 0; --k) most = std::max(a[k], most);
      return most;
    }
    case VoronoiMetric::Minkowski: {
      VecN<D> powered;
      for (int k = 0; k < D; ++k) powered[k] = std::pow(a[k], exponent);
      return std::pow(reduce_add<D>(powered), 1.0f / exponent);
    }
  }
  return 0.0f;
}

struct Octaves {
  float detail, roughness, lacunarity;
  bool normalize;
  bool integer_hash;          // Cycles 5.0+'s cells (voronoi_search::cell_words)
  float max_distance = 0.0f;  // the largest distance the feature has, which Normalize divides by
  bool single() const { return detail == 0.0f || roughness == 0.0f; }
};

// The largest distance of a feature point (or edge) at Randomness q.randomness.
template <int D>
float max_distance(VoronoiFeature feature, const Params& q) {
  const float half = 0.5f + 0.5f * q.randomness;
  if (feature == VoronoiFeature::DistanceToEdge) return half;
  const float d = D == 1 ? half : metric_length<D>(VecN<D>(half), q.metric, q.exponent);
  return feature == VoronoiFeature::F2 ? d * 2.0f : d;
}

// One octave of F1, F2 or Smooth F1 (Smoothness 0: F1).
template <int D>
Found<D> point_octave(const VecN<D>& p, VoronoiFeature feature, const Params& q) {
  if (feature == VoronoiFeature::F2) return f2<D>(p, q);
  if (feature == VoronoiFeature::SmoothF1 && q.smoothness != 0.0f) return smooth_f1<D>(p, q);
  return f1<D>(p, q);
}

// F1, F2 and Smooth F1 over the octaves: distances and colours summed, positions blended.
template <int D>
Found<D> fractal_points(const VecN<D>& p, VoronoiFeature feature, const Params& q, const Octaves& o) {
  float amplitude = 1.0f, max_amplitude = 0.0f, scale = 1.0f;
  Found<D> out;
  const float last = std::ceil(o.detail);
  for (int i = 0; float(i) <= last; ++i) {
    const Found<D> octave = point_octave<D>(p * scale, feature, q);
    if (o.single()) {
      max_amplitude = 1.0f;
      out = octave;
      break;
    }
    const VecN<D> position = octave.position * (1.0f / scale);
    if (float(i) <= o.detail) {
      max_amplitude += amplitude;
      out.distance += octave.distance * amplitude;
      out.color += octave.color * amplitude;
      out.position = lerp(out.position, position, amplitude);
      scale *= o.lacunarity;
      amplitude *= o.roughness;
    } else if (const float fraction = o.detail - std::floor(o.detail); fraction != 0.0f) {
      max_amplitude = lerp(max_amplitude, max_amplitude + amplitude, fraction);
      out.distance = lerp(out.distance, out.distance + octave.distance * amplitude, fraction);
      out.color = lerp(out.color, out.color + octave.color * amplitude, fraction);
      out.position = lerp(out.position, lerp(out.position, position, amplitude), fraction);
    }
  }
  if (o.normalize) {
    out.distance /= max_amplitude * o.max_distance;
    out.color *= 1.0f / max_amplitude;
  }
  return out;
}

// Distance to Edge over the octaves: a running minimum of the octaves' distances (each in the
// first octave's units), each octave blended in by its weight.
template <int D>
float fractal_edge(const VecN<D>& p, const Params& q, const Octaves& o) {
  float amplitude = 1.0f, max_amplitude = o.max_distance, scale = 1.0f, distance = 8.0f;
  const float last = std::ceil(o.detail);
  for (int i = 0; float(i) <= last; ++i) {
    const float octave = distance_to_edge<D>(p * scale, q.randomness, true, q.integer_hash);
    if (o.single()) {
      distance = octave;
      break;
    }
    const float closer = cycles_min(distance, octave / scale);
    if (float(i) <= o.detail) {
      max_amplitude = lerp(max_amplitude, o.max_distance / scale, amplitude);
      distance = lerp(distance, closer, amplitude);
      scale *= o.lacunarity;
      amplitude *= o.roughness;
    } else if (const float fraction = o.detail - std::floor(o.detail); fraction != 0.0f) {
      max_amplitude = lerp(max_amplitude, lerp(max_amplitude, o.max_distance / scale, amplitude), fraction);
      distance = lerp(distance, cycles_min(distance, lerp(distance, closer, amplitude)), fraction);
    }
  }
  return o.normalize ? distance / max_amplitude : distance;
}

// Cycles 4.x's search for a feature, positions in the node's coordinates (times 1 / Scale).
template <int D>
Found<D> search4(const VecN<D>& p, VoronoiFeature feature, const Params& q, Octaves o, float node_scale) {
  Found<D> out;
  o.max_distance = max_distance<D>(feature, q);
  switch (feature) {
    case VoronoiFeature::NSphereRadius:
      out.radius = n_sphere_radius<D>(p, q.randomness, FLT_MAX, q.integer_hash);
      break;
    case VoronoiFeature::DistanceToEdge: out.distance = fractal_edge<D>(p, q, o); break;
    default:
      out = fractal_points<D>(p, feature, q, o);
      out.position = node_scale != 0.0f ? out.position * (1.0f / node_scale) : VecN<D>(0.0f);
  }
  return out;
}


Octaves octaves_of(const VoronoiFractal& f) {
  return {clamp_to(f.detail, 0.0f, 15.0f), clamp_to(f.roughness, 0.0f, 1.0f), f.lacunarity, f.normalize,
          f.integer_hash};
}

VoronoiOutputs evaluate(const VoronoiSettings& settings, const VoronoiInputs& in, const Octaves& octaves,
                        bool color) {
  const Params q{clamp_to(in.smoothness / 2.0f, 0.0f, 0.5f),
                 in.exponent,
                 clamp_to(in.randomness, 0.0f, 1.0f),
                 settings.metric,
                 color,
                 true,
                 FLT_MAX,
                 octaves.integer_hash};
  return for_dimensions(settings.dimensions, [&](auto dimensions) {
    constexpr int D = decltype(dimensions)::value;
    return outputs_of<D>(search4<D>(coordinate<D>(in), settings.feature, q, octaves, in.scale));
  });
}

}  // namespace

VoronoiOutputs voronoi4(const VoronoiSettings& settings, const VoronoiInputs& in, const VoronoiFractal& fractal) {
  return evaluate(settings, in, octaves_of(fractal), true);
}

OpValue voronoi4_op(const ShaderOpContext& c) {
  if (c.ins.flags > (kVoronoiRadius | kVoronoiNormalize | kVoronoiIntegerHash)) return glm::vec4(0.0f);
  const Octaves octaves = octaves_of({c.value(6), c.value(7), c.value(8), (c.ins.flags & kVoronoiNormalize) != 0,
                                      (c.ins.flags & kVoronoiIntegerHash) != 0});
  return op_outputs(c, [&](const VoronoiSettings& settings, const VoronoiInputs& in, bool color) {
    return evaluate(settings, in, octaves, color);
  });
}

}  // namespace torrance::shader
