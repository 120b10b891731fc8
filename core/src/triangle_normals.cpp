#include "torrance/triangle_normals.h"

#include "torrance/first_failure.h"

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
}  // namespace

void triangle_normals(const float* positions, size_t num_vertices, const int32_t* triangles, size_t num_triangles,
                      float* normals, uint8_t* usable) {
  const size_t bad = first_failure<KeepDenormals>(num_triangles, [&](size_t i) {
    const int32_t* t = triangles + 3 * i;
    if (t[0] < 0 || t[1] < 0 || t[2] < 0 || size_t(t[0]) >= num_vertices || size_t(t[1]) >= num_vertices ||
        size_t(t[2]) >= num_vertices)
      return true;
    const float* p0 = positions + 3 * size_t(t[0]);
    const float* p1 = positions + 3 * size_t(t[1]);
    const float* p2 = positions + 3 * size_t(t[2]);
    const float a0 = p1[0] - p0[0], a1 = p1[1] - p0[1], a2 = p1[2] - p0[2];
    const float b0 = p2[0] - p0[0], b1 = p2[1] - p0[1], b2 = p2[2] - p0[2];
    const float x = a1 * b2 - a2 * b1, y = a2 * b0 - a0 * b2, z = a0 * b1 - a1 * b0;
    float sum = x * x;
    sum += y * y;
    sum += z * z;
    const float length = std::sqrt(sum);
    const bool ok = length > 1e-30f && std::isfinite(length);
    float* n = normals + 3 * i;
    n[0] = ok ? x / length : 0.0f;
    n[1] = ok ? y / length : 0.0f;
    n[2] = ok ? z / length : 0.0f;
    usable[i] = ok;
    return false;
  });
  if (bad < num_triangles) {
    const int32_t* t = triangles + 3 * bad;
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || size_t(t[k]) >= num_vertices)
        throw std::invalid_argument("triangle " + std::to_string(bad) + " uses vertex index " + std::to_string(t[k]) +
                                    ", outside [0, " + std::to_string(num_vertices) + ")");
  }
}

}  // namespace torrance
