#include "torrance/scene/vertex_normals.h"

#include "torrance/util/first_failure.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

// Products and sums round one by one, in float, as Blender's own (no fused multiply-add).
#pragma GCC optimize("fp-contract=off")

namespace torrance {
namespace {

using Vec3f = std::array<float, 3>;

Vec3f position(const float* positions, int32_t v) {
  const float* p = positions + 3 * size_t(v);
  return {p[0], p[1], p[2]};
}

Vec3f minus(const Vec3f& a, const Vec3f& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

float dot(const Vec3f& a, const Vec3f& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// v scaled to unit length by the reciprocal of its length, as Blender does; false (and v = 0)
// where its squared length is not above 1e-35.
bool normalize(Vec3f& v) {
  const float squared = dot(v, v);
  if (!(squared > 1e-35f)) {
    v = {0.0f, 0.0f, 0.0f};
    return false;
  }
  const float scale = 1.0f / std::sqrt(squared);
  v = {v[0] * scale, v[1] * scale, v[2] * scale};
  return true;
}

// The polygon's unit normal by Newell's method (each edge adds (a - b) x-wise products of the
// other two coordinates' differences and sums); (0, 0, 1) where it has none, as in Blender.
Vec3f polygon_normal(const float* positions, const int32_t* corners, size_t n) {
  Vec3f sum{0.0f, 0.0f, 0.0f};
  Vec3f a = position(positions, corners[n - 1]);
  for (size_t c = 0; c < n; ++c) {
    const Vec3f b = position(positions, corners[c]);
    sum[0] += (a[1] - b[1]) * (a[2] + b[2]);
    sum[1] += (a[2] - b[2]) * (a[0] + b[0]);
    sum[2] += (a[0] - b[0]) * (a[1] + b[1]);
    a = b;
  }
  if (!normalize(sum)) sum = {0.0f, 0.0f, 1.0f};
  return sum;
}

// The angle at corner c of a polygon of n corners: between its edges to the previous and the
// next corner, each normalised (an edge of length 0 counts as 0, so a right angle).
float corner_angle(const float* positions, const int32_t* corners, size_t n, size_t c) {
  const Vec3f at = position(positions, corners[c]);
  Vec3f from_prev = minus(position(positions, corners[(c + n - 1) % n]), at);
  Vec3f to_next = minus(at, position(positions, corners[(c + 1) % n]));
  normalize(from_prev);
  normalize(to_next);
  const float cosine = -dot(from_prev, to_next);
  if (cosine <= -1.0f) return float(M_PI);
  if (cosine >= 1.0f) return 0.0f;
  return std::acos(cosine);
}

}  // namespace

void vertex_normals(const float* positions, size_t num_vertices, const int32_t* corner_vertices, size_t num_corners,
                    const int32_t* polygon_starts, const int32_t* polygon_sizes, size_t num_polygons, float* out) {
  const size_t bad_corner = first_failure(num_corners, [&](size_t i) {
    return corner_vertices[i] < 0 || size_t(corner_vertices[i]) >= num_vertices;
  });
  if (bad_corner < num_corners)
    throw std::invalid_argument("corner " + std::to_string(bad_corner) + " uses vertex index " +
                                std::to_string(corner_vertices[bad_corner]) + ", outside [0, " +
                                std::to_string(num_vertices) + ")");
  const size_t bad_polygon = first_failure(num_polygons, [&](size_t p) {
    return polygon_starts[p] < 0 || polygon_sizes[p] < 0 ||
           size_t(polygon_starts[p]) + size_t(polygon_sizes[p]) > num_corners;
  });
  if (bad_polygon < num_polygons)
    throw std::invalid_argument("polygon " + std::to_string(bad_polygon) + " has corners [" +
                                std::to_string(polygon_starts[bad_polygon]) + ", " +
                                std::to_string(int64_t(polygon_starts[bad_polygon]) + polygon_sizes[bad_polygon]) +
                                "), outside [0, " + std::to_string(num_corners) + ")");
  // Each polygon's normal times each of its corners' angles, in parallel (each on its own: the
  // same whatever the threads).
  std::vector<Vec3f> terms(num_corners, Vec3f{0.0f, 0.0f, 0.0f});
  tbb::parallel_for(tbb::blocked_range<size_t>(0, num_polygons, 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t p = r.begin(); p != r.end(); ++p) {
      const size_t start = size_t(polygon_starts[p]), n = size_t(polygon_sizes[p]);
      if (n < 3) continue;
      const int32_t* corners = corner_vertices + start;
      const Vec3f normal = polygon_normal(positions, corners, n);
      for (size_t c = 0; c < n; ++c) {
        const float angle = corner_angle(positions, corners, n, c);
        terms[start + c] = {normal[0] * angle, normal[1] * angle, normal[2] * angle};
      }
    }
  });
  // The sums, in float, polygon by polygon: what Blender's threads give when they take the
  // polygons in order.
  std::vector<Vec3f> sums(num_vertices, Vec3f{0.0f, 0.0f, 0.0f});
  for (size_t p = 0; p < num_polygons; ++p) {
    const size_t start = size_t(polygon_starts[p]), n = size_t(polygon_sizes[p]);
    if (n < 3) continue;
    for (size_t c = start; c < start + n; ++c) {
      Vec3f& sum = sums[size_t(corner_vertices[c])];
      for (size_t k = 0; k < 3; ++k) sum[k] += terms[c][k];
    }
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, num_vertices, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t v = r.begin(); v != r.end(); ++v) {
      Vec3f normal = sums[v];
      if (!normalize(normal)) {
        normal = position(positions, int32_t(v));
        normalize(normal);
      }
      if (!(std::isfinite(normal[0]) && std::isfinite(normal[1]) && std::isfinite(normal[2])))
        normal = {0.0f, 0.0f, 0.0f};
      for (size_t k = 0; k < 3; ++k) out[3 * v + k] = normal[k];
    }
  });
}

}  // namespace torrance
