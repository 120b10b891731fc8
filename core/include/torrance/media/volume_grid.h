// A sparse brick grid: the voxels of one grid of a Volume object (an OpenVDB grid the add-on
// reads) or of a fluid simulation's smoke domain, kept as the bricks of kBrickSize^3 voxels that
// hold anything (empty space costs one index entry per brick). Voxel centres lie at integer
// index coordinates (OpenVDB's convention); a world point reaches index space through the grid's
// world_to_index transform. Lookups are trilinear over the 8 voxels around the point (Cycles'
// default Linear volume interpolation), voxels outside any brick 0. Each brick also keeps the
// largest component of its voxels and of its neighbours' (the apron a trilinear lookup reads), a
// bound the free-flight tracking's majorant is made from (varying_tracking.h).
#pragma once

#include "torrance/util/math.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace torrance {

struct ShaderOpContext;
struct OpValue;

class VolumeGrid {
 public:
  static constexpr int kBrickSize = 8;
  static constexpr int kBrickVoxels = kBrickSize * kBrickSize * kBrickSize;

  // channels: 1 (a scalar grid) to 4 (RGBA); origins: each brick's first voxel (index space, a
  // multiple of kBrickSize on each axis); values: bricks x kBrickVoxels x channels floats, x
  // fastest, then y, then z. NaN and infinite voxels are read as 0. Throws
  // std::invalid_argument for a bad shape, an unaligned or repeated origin, or a singular or
  // non-finite transform.
  VolumeGrid(int channels, const Mat4& world_to_index, const std::vector<glm::ivec3>& origins,
             const std::vector<float>& values);

  // Lookups outside the index-space box [lo, hi] read 0 (Cycles 3.4's dense volume textures
  // end at the grid's active bounding box). Throws std::invalid_argument unless lo <= hi.
  void clip(const Vec3& lo, const Vec3& hi);

  // RGBA at world point p: a scalar grid's value v as (v, v, v, 1), a colour grid's channels
  // (alpha 1 without a fourth).
  glm::vec4 lookup(const Vec3& world) const;
  // The largest channel of the voxels any trilinear lookup in p's brick reads (0 outside).
  float brick_max(const Vec3& world) const;
  // The world-space centres of the bricks that hold anything (for the majorant's search).
  std::vector<Vec3> brick_centres() const;
  int channels() const { return channels_; }
  size_t bricks() const { return origins_.size(); }

 private:
  glm::vec4 voxel(const glm::ivec3& i) const;
  int32_t brick_at(const glm::ivec3& brick) const;  // -1: none

  int channels_;
  Mat4 world_to_index_, index_to_world_;
  Vec3 clip_lo_{-INFINITY}, clip_hi_{INFINITY};
  glm::ivec3 lo_{0}, dims_{0};  // the brick lattice's first brick and its size, in bricks
  std::vector<int32_t> index_;  // brick lattice cell -> brick, -1: empty
  std::vector<glm::ivec3> origins_;
  std::vector<float> values_;
  std::vector<float> max_;  // per lattice cell: the largest channel over it and its neighbours
};

// The VolumeGrid shader op (shader_program.h): grid ins.resource of the globals' grids at the
// world point in0, RGBA as lookup gives it; with the globals' grid_bounds its brick's bound in
// every channel. 0 without grids or for an id past them.
OpValue volume_grid_op(const ShaderOpContext& c);

}  // namespace torrance
