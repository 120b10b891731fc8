#include "torrance/scene/world_mesh.h"

#include "torrance/util/first_failure.h"

#include <emmintrin.h>
#include <xmmintrin.h>

#include <cmath>
#include <stdexcept>
#include <string>

// Products and sums must round one by one, as numpy's: no fused multiply-add.
#pragma GCC optimize("fp-contract=off")

namespace torrance {
namespace {
// IEEE denormals on this thread while it lives: TBB's workers may come from a render, which
// flushes them to zero (FlushDenormals in integrator.cpp), and numpy does not.
class KeepDenormals {
 public:
  KeepDenormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ & ~0x8040u); }
  ~KeepDenormals() { _mm_setcsr(saved_); }

 private:
  unsigned saved_;
};

bool outside(const int32_t* t, size_t num_vertices) {
  return t[0] < 0 || t[1] < 0 || t[2] < 0 || size_t(t[0]) >= num_vertices || size_t(t[1]) >= num_vertices ||
         size_t(t[2]) >= num_vertices;
}

// Throws for triangle `bad` if it is one (bad < num_triangles): the message names its index outside.
void check_indices(const int32_t* triangles, size_t num_triangles, size_t num_vertices, size_t bad) {
  if (bad >= num_triangles) return;
  const int32_t* t = triangles + 3 * bad;
  for (int k = 0; k < 3; ++k)
    if (t[k] < 0 || size_t(t[k]) >= num_vertices)
      throw std::invalid_argument("triangle " + std::to_string(bad) + " uses vertex index " + std::to_string(t[k]) +
                                  ", outside [0, " + std::to_string(num_vertices) + ")");
}

// v / |v| into out as numpy's _normalize computes it; false (and 0) where |v| is not finite or
// not above 1e-30.
bool normalize_into(float x, float y, float z, float* out) {
  float sum = x * x;
  sum += y * y;
  sum += z * z;
  const float length = std::sqrt(sum);
  const bool ok = length > 1e-30f && std::isfinite(length);
  out[0] = ok ? x / length : 0.0f;
  out[1] = ok ? y / length : 0.0f;
  out[2] = ok ? z / length : 0.0f;
  return ok;
}
}  // namespace

void triangle_normals(const float* positions, size_t num_vertices, const int32_t* triangles, size_t num_triangles,
                      float* normals, uint8_t* usable) {
  const size_t bad = first_failure<KeepDenormals>(num_triangles, [&](size_t i) {
    const int32_t* t = triangles + 3 * i;
    if (outside(t, num_vertices)) return true;
    const float* p0 = positions + 3 * size_t(t[0]);
    const float* p1 = positions + 3 * size_t(t[1]);
    const float* p2 = positions + 3 * size_t(t[2]);
    const float a0 = p1[0] - p0[0], a1 = p1[1] - p0[1], a2 = p1[2] - p0[2];
    const float b0 = p2[0] - p0[0], b1 = p2[1] - p0[1], b2 = p2[2] - p0[2];
    usable[i] = normalize_into(a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0, normals + 3 * i);
    return false;
  });
  check_indices(triangles, num_triangles, num_vertices, bad);
}

void transform_points(const float* points, size_t count, const double* m, float* out) {
  first_failure<KeepDenormals>(count, [&](size_t i) {
    const double x = points[3 * i], y = points[3 * i + 1], z = points[3 * i + 2];
    for (int r = 0; r < 3; ++r) {
      const double* row = m + 4 * r;
      const double v = ((x * row[0] + y * row[1]) + z * row[2]) + row[3];
      // Rounded by the hardware (to nearest; beyond float's range to +-Inf), as numpy's cast:
      // a C++ conversion of an out-of-range double is undefined.
      out[3 * i + size_t(r)] = _mm_cvtss_f32(_mm_cvtsd_ss(_mm_setzero_ps(), _mm_set_sd(v)));
    }
    return false;
  });
}

void corner_normals(const float* normals, size_t num_normals, bool per_vertex, const int32_t* triangles,
                    size_t num_triangles, const float* m, const uint8_t* smooth, const float* geometric, float* out) {
  if (!per_vertex && num_normals != 3 * num_triangles)
    throw std::invalid_argument("corner normals: " + std::to_string(num_normals) + " normals for " +
                                std::to_string(num_triangles) + " triangles (3 per triangle expected)");
  const size_t bad = first_failure<KeepDenormals>(num_triangles, [&](size_t i) {
    const int32_t* t = triangles + 3 * i;
    if (per_vertex && outside(t, num_normals)) return true;
    const float* ng = geometric + 3 * i;
    const bool flat = smooth && !smooth[i];
    for (int k = 0; k < 3; ++k) {
      float* corner = out + 9 * i + 3 * size_t(k);
      const float* v = normals + 3 * (per_vertex ? size_t(t[k]) : 3 * i + size_t(k));
      bool ok;
      if (m)
        ok = normalize_into((v[0] * m[0] + v[1] * m[1]) + v[2] * m[2], (v[0] * m[3] + v[1] * m[4]) + v[2] * m[5],
                            (v[0] * m[6] + v[1] * m[7]) + v[2] * m[8], corner);
      else
        ok = normalize_into(v[0], v[1], v[2], corner);
      if (flat || !ok) corner[0] = ng[0], corner[1] = ng[1], corner[2] = ng[2];
    }
    return false;
  });
  check_indices(triangles, num_triangles, num_normals, bad);
}

}  // namespace torrance
