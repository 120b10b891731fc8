// The Point Density node's voxel lookup (shader_voxel.h), in the order of Cycles' CPU
// TextureInterpolator::interp_3d.
#include "torrance/shader/shader_voxel.h"

#include "torrance/shader/cubic_bspline.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace torrance::shader {

namespace {

// A voxel's RGBA; with clip_texels, 0 for one outside the grid, else the nearest edge voxel's.
glm::vec4 voxel(const float* voxels, const glm::ivec3& n, glm::ivec3 i, bool clip_texels) {
  if (clip_texels) {
    if (glm::any(glm::lessThan(i, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(i, n))) return glm::vec4(0.0f);
  } else {
    i = glm::clamp(i, glm::ivec3(0), n - 1);
  }
  const float* v = voxels + ((size_t(i.z) * size_t(n.y) + size_t(i.y)) * size_t(n.x) + size_t(i.x)) * 4;
  return {v[0], v[1], v[2], v[3]};
}

// Per axis: the first of the `taps` voxels a lookup weighs and their weights.
struct Taps {
  glm::ivec3 first{0};
  std::array<std::array<float, 4>, 3> weights{};
};

}  // namespace

glm::vec4 voxel_lookup(const float* voxels, const glm::ivec3& n, const Vec3& p, VoxelInterpolation interpolation,
                       uint8_t clip) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return glm::vec4(0.0f);
  const bool clip_texels = clip == kVoxelClipTexels;
  if (!clip_texels && (glm::any(glm::lessThan(p, Vec3(0.0f))) || glm::any(glm::greaterThan(p, Vec3(1.0f)))))
    return glm::vec4(0.0f);
  // Far outside, every lookup reads nothing; the clamp keeps the voxel arithmetic in int.
  const Vec3 scaled = glm::clamp(p, Vec3(-4.0f), Vec3(5.0f)) * Vec3(n);
  if (interpolation == VoxelInterpolation::Closest) return voxel(voxels, n, glm::ivec3(glm::floor(scaled)), clip_texels);
  const Vec3 at = scaled - 0.5f;
  const Vec3 floor_at = glm::floor(at);
  const Vec3 t = at - floor_at;
  const bool cubic = interpolation == VoxelInterpolation::Cubic;
  const int taps = cubic ? 4 : 2;
  Taps k;
  k.first = glm::ivec3(floor_at) - (cubic ? 1 : 0);
  for (int axis = 0; axis < 3; ++axis)
    k.weights[size_t(axis)] = cubic ? cubic_bspline_weights(t[axis]) : std::array<float, 4>{1.0f - t[axis], t[axis]};
  glm::vec4 sum(0.0f);
  for (int z = 0; z < taps; ++z)
    for (int y = 0; y < taps; ++y) {
      glm::vec4 row(0.0f);
      for (int x = 0; x < taps; ++x)
        row += k.weights[0][size_t(x)] * voxel(voxels, n, k.first + glm::ivec3(x, y, z), clip_texels);
      sum += (k.weights[1][size_t(y)] * k.weights[2][size_t(z)]) * row;
    }
  return sum;
}

OpValue point_density_op(const ShaderOpContext& c) {
  const float* table = c.data;
  if (c.data_size < kVoxelHeader) return glm::vec4(0.0f);
  const glm::ivec3 n{int(table[0]), int(table[1]), int(table[2])};
  if (n.x < 1 || n.y < 1 || n.z < 1 ||
      double(kVoxelHeader) + 4.0 * double(n.x) * double(n.y) * double(n.z) != double(c.data_size))
    return glm::vec4(0.0f);
  if (c.globals.grid_bounds) return {table[15], table[16], table[17], table[18]};
  const Vec3 q = c.vector(0);
  const float* m = table + 3;
  const Vec3 p(m[0] * q.x + m[1] * q.y + m[2] * q.z + m[3], m[4] * q.x + m[5] * q.y + m[6] * q.z + m[7],
               m[8] * q.x + m[9] * q.y + m[10] * q.z + m[11]);
  return voxel_lookup(table + kVoxelHeader, n, p, VoxelInterpolation(c.ins.mode), c.ins.flags & 1);
}

}  // namespace torrance::shader
