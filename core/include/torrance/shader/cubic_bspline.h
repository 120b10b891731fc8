// The uniform cubic B-spline Cycles' CPU image lookups interpolate with (Cubic: 4 texels per
// axis, 2-D images and 3-D voxel textures alike).
#pragma once

#include <array>

namespace torrance {

// The weights of the four texels around a point t (in [0, 1)) past the second one; they are
// non-negative and sum to 1.
inline std::array<float, 4> cubic_bspline_weights(float t) {
  return {(((-1.0f / 6.0f) * t + 0.5f) * t - 0.5f) * t + 1.0f / 6.0f, ((0.5f * t - 1.0f) * t) * t + 2.0f / 3.0f,
          ((-0.5f * t + 0.5f) * t + 0.5f) * t + 1.0f / 6.0f, (1.0f / 6.0f) * t * t * t};
}

}  // namespace torrance
