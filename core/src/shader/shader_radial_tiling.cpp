// Blender 5.0+'s Radial Tiling node as Cycles computes it: see shader_radial_tiling.h.
#include "torrance/shader/shader_radial_tiling.h"

#include <cmath>

namespace torrance::shader {

namespace {

inline float sqr(float x) { return x * x; }
inline float negated_below(float p, float a, float bisector) { return a < bisector ? -p : p; }

// The point's segment: its angle from the x axis in [0, 2 pi), the half angle, the segment id
// and the angle within the segment.
struct Segment {
  float angle, half, width, id, within;
};

Segment segment_of(const Vec2& coord, float sides) {
  Segment s;
  s.angle = std::atan2(coord.y, coord.x) + float(coord.y < 0.0f) * kTwoPi;
  s.half = kPi / sides;
  s.width = 2.0f * s.half;
  s.id = std::floor(s.angle / s.width);
  s.within = s.angle - s.id * s.width;
  return s;
}

// The straight polygon (Roundness 0) of whole Sides.
glm::vec4 straight(const Segment& s, float l, float sides, bool normalize) {
  const float distance = l * std::cos(s.half - s.within);
  float p = negated_below(distance * std::tan(std::fabs(s.half - s.within)), s.within, s.half);
  if (normalize && sides != 2.0f) p /= distance * std::tan(s.half);
  const float width = sides != 2.0f ? std::tan(s.half) : 0.0f;
  return {distance, p, width, s.id * s.width + s.half};
}

// Between 0 and 1: rounded near the dividers, straight between.
glm::vec4 rounded(const Segment& s, float l, float r, bool normalize) {
  const float bevel = s.half - std::atan((1.0f - r) * std::tan(s.half));
  const float bevel_to_bisector = s.half - bevel;
  const float spline = (1.0f - r) * bevel;
  const float width = std::tan(bevel_to_bisector) + spline + r * bevel;
  const float rotation = s.id * s.width + s.half;
  if (s.within >= s.width - bevel || s.within < bevel) {
    const float signed_angle = s.within - float(s.within > s.half) * s.width;
    const float centre = (1.0f - r) / std::cos(s.half);
    const float c = std::cos(signed_angle);
    const float ratio = c * centre + std::sqrt(sqr(c * centre) + sqr(r) - sqr(centre));
    const float distance = l / ratio;
    const float to_bevel = bevel - std::fabs(signed_angle);
    const float lc = l * std::cos(bevel_to_bisector);
    float p = l * std::sin(bevel_to_bisector);
    if (to_bevel < spline)
      p += l * std::cos(bevel_to_bisector) * to_bevel + 0.5f * (1.0f - lc) * sqr(to_bevel) / spline;
    else
      p += spline * (0.5f * l * std::cos(bevel_to_bisector) - 0.5f) + to_bevel;
    p = negated_below(p, s.within, s.half);
    if (normalize) {
      const float by_distance =
          distance * std::tan(bevel_to_bisector) + spline * (0.5f * distance + 0.5f) + r * bevel;
      const float by_length =
          l * std::sin(bevel_to_bisector) + spline * (0.5f * l * std::cos(bevel_to_bisector) + 0.5f) + r * bevel;
      p /= by_distance + (to_bevel / bevel) * (by_length - by_distance);
    }
    return {distance, p, width, rotation};
  }
  const float distance = l * std::cos(s.half - s.within);
  float p = negated_below(distance * std::tan(std::fabs(s.half - s.within)), s.within, s.half);
  if (normalize) p /= distance * std::tan(bevel_to_bisector) + spline * (0.5f * distance + 0.5f) + r * bevel;
  return {distance, p, width, rotation};
}

// Fractional Sides at Roundness 0: whole segments, then the narrower last one.
glm::vec4 irregular_straight(const Segment& s, float l, float sides, bool normalize) {
  const float last = kPi - std::floor(sides) * s.half;  // the last segment's half angle
  if (s.angle < kTwoPi - 2.0f * last) {
    const float distance = l * std::cos(s.half - s.within);
    float p = negated_below(distance * std::tan(std::fabs(s.half - s.within)), s.within, s.half);
    if (normalize) p /= distance * std::tan(s.half);
    return {distance, p, std::tan(s.half), s.id * s.width + s.half};
  }
  const float k = std::cos(s.half) / std::cos(last);
  const float along_last = l * std::cos(last - s.within);
  float p = negated_below(k * along_last * std::tan(std::fabs(last - s.within)), s.within, last);
  if (normalize) p /= k * along_last * std::tan(last);
  return {k * along_last, p, std::tan(last), s.id * s.width + last};
}

}  // namespace

glm::vec4 radial_tiling(const Vec2& coord, float sides, float roundness, bool normalize) {
  const float l = std::sqrt(sqr(coord.x) + sqr(coord.y));
  const Segment s = segment_of(coord, sides);
  glm::vec4 out;
  if (sides - std::floor(sides) == 0.0f) {
    if (roundness == 0.0f) {
      out = straight(s, l, sides, normalize);
    } else if (roundness == 1.0f) {
      float p = negated_below(std::fabs(s.half - s.within), s.within, s.half);
      if (normalize) p /= s.half;
      out = {l, p, s.half, s.id * s.width + s.half};
    } else {
      out = rounded(s, l, roundness, normalize);
    }
  } else {
    out = irregular_straight(s, l, sides, normalize);  // (Roundness above 0: not done, see .h)
  }
  if (coord.x == 0.0f && coord.y == 0.0f) out.y = 0.0f;
  if (normalize)
    out.y = 0.5f * out.y + 0.5f;
  else
    out.x -= 1.0f;
  return out;
}

float radial_tiling_segment_id(const Vec2& coord, float sides) {
  return std::floor(sides * ((std::atan2(coord.y, coord.x) / kTwoPi) + float(coord.y < 0.0f)));
}

OpValue radial_tiling_op(const ShaderOpContext& c) {
  const Vec2 coord(c.in(0));
  const float sides = std::fmax(c.value(1), 2.0f);
  const float r = c.value(2);
  const float roundness = r > 0.0f ? (r < 1.0f ? r : 1.0f) : 0.0f;
  if (c.ins.mode == 0) {
    const glm::vec4 v = radial_tiling(coord, sides, roundness, c.ins.flags & 1);
    return {v.y, v.x, 0.0f, 0.0f};
  }
  const glm::vec4 v = radial_tiling(coord, sides, roundness, c.ins.flags & 1);
  return {radial_tiling_segment_id(coord, sides), v.z, v.w, 0.0f};
}

}  // namespace torrance::shader
