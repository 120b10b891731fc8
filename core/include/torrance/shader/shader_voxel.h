// The Point Density texture node (opcode 64 of the texture family) as Cycles renders it
// (svm/voxel.h: the point mapped into the unit box, then its 3-D image lookup of the voxels
// Blender computed, kernel_tex_image_interp_3d with the node's Interpolation and Clip extension):
//   TexPointDensity (64)  in0 the point (the node's Vector, in the space the add-on moved it to);
//     a table: nx, ny, nz (the voxel counts, as floats), 12 floats of the 3 x 4 affine map taking
//     the point into the unit box (row-major: its x row, y row, z row, each ending with the
//     translation), the 4 channels' largest voxel values, then nx ny nz RGBA voxels (x fastest,
//     then y, then z; Blender's calc_point_density order)
//   mode: VoxelInterpolation; flags: VoxelClip
// The output is RGBA: Color the xyz, Density the w. With the globals' grid_bounds (a volume's
// majorant search) the op gives the channels' largest values, a bound of every lookup (the
// three interpolations weigh voxels by non-negative weights summing to 1). A table of the wrong
// size gives 0. python_addon/torrance/shader_graph/point_density.py fills it.
#pragma once

#include "torrance/shader/shader_program.h"

namespace torrance::shader {

enum class VoxelInterpolation : uint8_t { Closest, Linear, Cubic };
constexpr int kVoxelInterpolations = int(VoxelInterpolation::Cubic) + 1;

// How a lookup treats the unit box's border (flags):
//   kVoxelClipBox: Cycles 3.4's CPU Clip: 0 outside [0, 1]^3; inside, the neighbours past an
//     edge are the edge voxels (the lookup then clamped, as Extend).
//   kVoxelClipTexels: 0 where no voxel the lookup weighs lies in the grid; voxels past an edge
//     read 0 (a lookup fades out over the border's half voxel, Linear, or two, Cubic).
constexpr uint8_t kVoxelClipBox = 0, kVoxelClipTexels = 1;

constexpr int kVoxelHeader = 19;  // nx, ny, nz, the 3 x 4 map, the 4 channel maxima

// The RGBA of the voxels at unit-box point p (0 .. 1 across the grid, voxel i's centre at
// (i + 0.5) / n), as Cycles' CPU interp_3d: voxels (nx ny nz RGBA, x fastest).
glm::vec4 voxel_lookup(const float* voxels, const glm::ivec3& n, const Vec3& p, VoxelInterpolation interpolation,
                       uint8_t clip);

OpValue point_density_op(const ShaderOpContext& c);

}  // namespace torrance::shader
