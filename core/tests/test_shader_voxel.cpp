// The Point Density node's voxel lookup (core/src/shader/shader_voxel.cpp) as Cycles' CPU 3-D
// image lookup: Closest, Linear and Cubic over a known grid, the unit box's border (Cycles 3.4's
// Clip and the texel-wise one), and the op run in a program (its affine map, its table's checks,
// the majorant's bound).
#include "torrance/shader/shader_program.h"
#include "torrance/shader/shader_voxel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace torrance {
namespace {

using shader::kVoxelClipBox;
using shader::kVoxelClipTexels;
using shader::voxel_lookup;
using shader::VoxelInterpolation;

// A grid of n voxels whose RGBA at (i, j, k) is (i, j, k, i + 10 j + 100 k).
std::vector<float> ramp_grid(const glm::ivec3& n) {
  std::vector<float> v;
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) v.insert(v.end(), {float(i), float(j), float(k), float(i + 10 * j + 100 * k)});
  return v;
}

// The unit-box point of voxel coordinates c (voxel i's centre at i + 0.5).
Vec3 unit(const Vec3& c, const glm::ivec3& n) { return c / Vec3(n); }

constexpr float kTol = 1e-5f;

TEST(ShaderVoxel, ClosestReadsTheVoxelHolding) {
  const glm::ivec3 n(4, 3, 5);
  const std::vector<float> g = ramp_grid(n);
  // Anywhere inside voxel (2, 1, 3), its centre or near its corners.
  for (const Vec3 c : {Vec3(2.5f, 1.5f, 3.5f), Vec3(2.01f, 1.99f, 3.01f), Vec3(2.99f, 1.01f, 3.99f)}) {
    const glm::vec4 r = voxel_lookup(g.data(), n, unit(c, n), VoxelInterpolation::Closest, kVoxelClipBox);
    EXPECT_EQ(r, glm::vec4(2.0f, 1.0f, 3.0f, 312.0f)) << c.x << " " << c.y << " " << c.z;
  }
  // p = 1 exactly is in the box: the last voxel.
  EXPECT_EQ(voxel_lookup(g.data(), n, Vec3(1.0f), VoxelInterpolation::Closest, kVoxelClipBox).w, 3.0f + 20.0f + 400.0f);
}

TEST(ShaderVoxel, LinearBetweenCentres) {
  const glm::ivec3 n(4, 3, 5);
  const std::vector<float> g = ramp_grid(n);
  // The ramp is linear in each index, so inside the centres' box the lookup is the ramp itself.
  const Vec3 c(1.8f, 1.25f, 2.6f);  // voxel coordinates of a point: index c - 0.5
  const glm::vec4 r = voxel_lookup(g.data(), n, unit(c, n), VoxelInterpolation::Linear, kVoxelClipBox);
  const Vec3 i = c - 0.5f;
  EXPECT_NEAR(r.x, i.x, kTol);
  EXPECT_NEAR(r.y, i.y, kTol);
  EXPECT_NEAR(r.z, i.z, kTol);
  EXPECT_NEAR(r.w, i.x + 10.0f * i.y + 100.0f * i.z, 1e-3f);
  // Within half a voxel of the box's face, the voxels past it are the edge's (Cycles 3.4: clamped).
  const glm::vec4 edge = voxel_lookup(g.data(), n, unit(Vec3(0.2f, 1.5f, 2.5f), n), VoxelInterpolation::Linear,
                                      kVoxelClipBox);
  EXPECT_NEAR(edge.w, 0.0f + 10.0f + 200.0f, 1e-3f);
  // Texel-wise clip: the voxel past the face reads 0, weighed 1 - 0.7.
  const glm::vec4 faded = voxel_lookup(g.data(), n, unit(Vec3(0.2f, 1.5f, 2.5f), n), VoxelInterpolation::Linear,
                                       kVoxelClipTexels);
  EXPECT_NEAR(faded.w, 0.7f * 210.0f, 1e-3f);
}

TEST(ShaderVoxel, CubicIsTheBSpline) {
  // One voxel of density 1 in the middle of 5^3 zeros: at its centre the B-spline's (2/3)^3, half a
  // voxel off along x (t = 0.5 between it and the next) (23/48) (2/3)^2.
  const glm::ivec3 n(5);
  std::vector<float> g(size_t(5 * 5 * 5 * 4), 0.0f);
  g[((2 * 5 + 2) * 5 + 2) * 4 + 3] = 1.0f;
  const glm::vec4 centre = voxel_lookup(g.data(), n, unit(Vec3(2.5f), n), VoxelInterpolation::Cubic, kVoxelClipBox);
  EXPECT_NEAR(centre.w, 8.0f / 27.0f, kTol);
  const glm::vec4 off =
      voxel_lookup(g.data(), n, unit(Vec3(3.0f, 2.5f, 2.5f), n), VoxelInterpolation::Cubic, kVoxelClipBox);
  EXPECT_NEAR(off.w, (23.0f / 48.0f) * (4.0f / 9.0f), kTol);
  // Linear there: 1 at the centre, 1/2 half a voxel off.
  EXPECT_NEAR(voxel_lookup(g.data(), n, unit(Vec3(2.5f), n), VoxelInterpolation::Linear, kVoxelClipBox).w, 1.0f, kTol);
  // The ramp is reproduced by the spline (it reproduces linear functions), the edge voxels
  // repeated past the faces (a lookup near a face then bends toward the edge's value).
  const glm::ivec3 m(6, 6, 6);
  const std::vector<float> ramp = ramp_grid(m);
  const glm::vec4 r = voxel_lookup(ramp.data(), m, unit(Vec3(2.7f, 3.1f, 3.4f), m), VoxelInterpolation::Cubic,
                                   kVoxelClipBox);
  EXPECT_NEAR(r.x, 2.2f, kTol);
  EXPECT_NEAR(r.y, 2.6f, kTol);
  EXPECT_NEAR(r.z, 2.9f, kTol);
  const glm::vec4 near_face = voxel_lookup(ramp.data(), m, unit(Vec3(0.6f, 3.5f, 3.5f), m), VoxelInterpolation::Cubic,
                                           kVoxelClipBox);
  // Index 0.1: weights (w0..w3) of t = 0.1 over voxels (0 clamped, 0, 1, 2).
  const float t = 0.1f;
  const float w2 = ((-0.5f * t + 0.5f) * t + 0.5f) * t + 1.0f / 6.0f, w3 = t * t * t / 6.0f;
  EXPECT_NEAR(near_face.x, w2 * 1.0f + w3 * 2.0f, kTol);
}

TEST(ShaderVoxel, OutsideTheBox) {
  const glm::ivec3 n(3, 3, 3);
  std::vector<float> ones(size_t(27 * 4), 1.0f);
  for (const auto interpolation : {VoxelInterpolation::Closest, VoxelInterpolation::Linear, VoxelInterpolation::Cubic}) {
    for (const Vec3 p : {Vec3(-0.001f, 0.5f, 0.5f), Vec3(0.5f, 1.001f, 0.5f), Vec3(0.5f, 0.5f, 7.0f),
                         Vec3(-1e30f, 0.5f, 0.5f), Vec3(NAN, 0.5f, 0.5f), Vec3(0.5f, INFINITY, 0.5f)})
      EXPECT_EQ(voxel_lookup(ones.data(), n, p, interpolation, kVoxelClipBox), glm::vec4(0.0f))
          << int(interpolation) << " at " << p.x << " " << p.y << " " << p.z;
    // Just inside, a constant grid reads its constant (the clamped neighbours are ones).
    EXPECT_NEAR(voxel_lookup(ones.data(), n, Vec3(0.001f, 0.999f, 0.5f), interpolation, kVoxelClipBox).w, 1.0f, kTol);
  }
  // Texel-wise: half a voxel past the face a Linear lookup still reads half the edge voxel;
  // a voxel past it nothing; Cubic reaches two voxels out.
  EXPECT_NEAR(voxel_lookup(ones.data(), n, Vec3(0.5f, 0.5f, 1.0f), VoxelInterpolation::Linear, kVoxelClipTexels).w,
              0.5f, kTol);
  EXPECT_EQ(voxel_lookup(ones.data(), n, Vec3(0.5f, 0.5f, 1.5f), VoxelInterpolation::Linear, kVoxelClipTexels),
            glm::vec4(0.0f));
  EXPECT_GT(voxel_lookup(ones.data(), n, Vec3(0.5f, 0.5f, 1.4f), VoxelInterpolation::Cubic, kVoxelClipTexels).w, 0.0f);
}

// A one-instruction program: the op at constant point q over `table`, mode, flags.
glm::vec4 run_point_density(const std::vector<float>& table, const Vec3& q, int mode, int flags, bool bounds = false) {
  ShaderInstruction ins;
  ins.op = ShaderOpcode::TexPointDensity;
  ins.mode = uint8_t(mode);
  ins.flags = uint8_t(flags);
  ins.resource = 0;
  ins.out = 1;
  ins.in[0] = 0;
  std::vector<float> data{float(table.size())};
  data.insert(data.end(), table.begin(), table.end());
  const ShaderProgram program({glm::vec4(q, 0.0f)}, {ins}, 2, 0, data);
  std::vector<glm::vec4> regs(2);
  ShaderGlobals g;
  g.grid_bounds = bounds;
  program.run(g, {}, regs.data());
  return regs[1];
}

TEST(ShaderVoxel, OpMapsThePointAndChecksItsTable) {
  EXPECT_EQ(int(ShaderOpcode::TexPointDensity), 64);
  EXPECT_EQ(shader_op_info(ShaderOpcode::TexPointDensity).modes, 3);
  EXPECT_TRUE(shader_op_info(ShaderOpcode::TexPointDensity).data);
  const glm::ivec3 n(4, 3, 5);
  const std::vector<float> grid = ramp_grid(n);
  // The box [-2, 2] x [0, 3] x [1, 6] (as Cycles' World space: (q - min) / (max - min)); the
  // maxima 3, 2, 4, 423.
  std::vector<float> table{4, 3, 5, 0.25f, 0, 0, 0.5f, 0, 1.0f / 3.0f, 0, 0, 0, 0, 0.2f, -0.2f, 3, 2, 4, 423};
  table.insert(table.end(), grid.begin(), grid.end());
  // Voxel (2, 1, 3)'s centre: unit (2.5/4, 1.5/3, 3.5/5) -> q = (0.5, 1.5, 4.5).
  EXPECT_EQ(run_point_density(table, Vec3(0.5f, 1.5f, 4.5f), 0, 0), glm::vec4(2.0f, 1.0f, 3.0f, 312.0f));
  const glm::vec4 linear = run_point_density(table, Vec3(0.5f, 1.5f, 4.5f), 1, 0);
  EXPECT_NEAR(linear.w, 312.0f, 1e-3f);
  // Outside the box: 0; the majorant's bound: the maxima wherever the point is.
  EXPECT_EQ(run_point_density(table, Vec3(2.1f, 1.5f, 4.5f), 2, 0), glm::vec4(0.0f));
  EXPECT_EQ(run_point_density(table, Vec3(9.0f), 1, 0, true), glm::vec4(3.0f, 2.0f, 4.0f, 423.0f));
  // A table one voxel short, or of no voxels, gives 0.
  std::vector<float> short_table(table.begin(), table.end() - 4);
  EXPECT_EQ(run_point_density(short_table, Vec3(0.5f, 1.5f, 4.5f), 0, 0), glm::vec4(0.0f));
  std::vector<float> empty(table.begin(), table.begin() + shader::kVoxelHeader);
  empty[0] = 0.0f;
  EXPECT_EQ(run_point_density(empty, Vec3(0.5f, 1.5f, 4.5f), 0, 0), glm::vec4(0.0f));
}

}  // namespace
}  // namespace torrance
