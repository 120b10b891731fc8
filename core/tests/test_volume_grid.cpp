// Sparse brick grids (media/volume_grid.h): trilinear lookups against a dense reference, empty
// grids and NaN voxels (nothing non-finite out), the bricks' bounds, and the transmittance of a
// constant-density box of bricks read by a heterogeneous volume's program against exp(-sigma d).
#include "torrance/media/volume_grid.h"
#include "torrance/scene/scene.h"

#include "media/varying_tracking.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace torrance {
namespace {

constexpr int B = VolumeGrid::kBrickSize;

// A dense scalar volume (nx, ny, nz), x fastest, as sparse bricks: the bricks with a non-zero voxel.
struct Bricks {
  std::vector<glm::ivec3> origins;
  std::vector<float> values;
};

Bricks bricks_of(const std::vector<float>& dense, const glm::ivec3& n, const glm::ivec3& offset) {
  Bricks out;
  for (int bz = 0; bz < n.z; bz += B)
    for (int by = 0; by < n.y; by += B)
      for (int bx = 0; bx < n.x; bx += B) {
        std::vector<float> brick(size_t(VolumeGrid::kBrickVoxels), 0.0f);
        bool any = false;
        for (int z = 0; z < B; ++z)
          for (int y = 0; y < B; ++y)
            for (int x = 0; x < B; ++x) {
              const glm::ivec3 v(bx + x, by + y, bz + z);
              if (v.x >= n.x || v.y >= n.y || v.z >= n.z) continue;
              const float value = dense[size_t((v.z * n.y + v.y) * n.x + v.x)];
              brick[size_t((z * B + y) * B + x)] = value;
              any = any || value != 0.0f;
            }
        if (!any) continue;
        out.origins.push_back(glm::ivec3(bx, by, bz) + offset);
        out.values.insert(out.values.end(), brick.begin(), brick.end());
      }
  return out;
}

// The dense volume's trilinear value at index point p (voxels outside it 0).
float dense_trilinear(const std::vector<float>& dense, const glm::ivec3& n, const Vec3& p) {
  const Vec3 f0 = glm::floor(p), f = p - f0;
  float sum = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const glm::ivec3 v = glm::ivec3(f0) + glm::ivec3(c & 1, (c >> 1) & 1, c >> 2);
    if (v.x < 0 || v.y < 0 || v.z < 0 || v.x >= n.x || v.y >= n.y || v.z >= n.z) continue;
    const float w = (c & 1 ? f.x : 1.0f - f.x) * (c & 2 ? f.y : 1.0f - f.y) * (c & 4 ? f.z : 1.0f - f.z);
    sum += w * dense[size_t((v.z * n.y + v.y) * n.x + v.x)];
  }
  return sum;
}

TEST(VolumeGrid, TrilinearLookupMatchesADenseReference) {
  // 21 x 13 x 30 voxels, half of the bricks empty (a sparse grid), placed at index offset
  // (-16, 8, 0) and reached through a rotated, scaled, moved world transform.
  const glm::ivec3 n(21, 13, 30), offset(-16, 8, 0);
  std::mt19937 gen(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> dense(size_t(n.x * n.y * n.z));
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x)
        dense[size_t((z * n.y + y) * n.x + x)] = ((x / B + z / B) % 2 == 0) ? u(gen) : 0.0f;
  const Bricks b = bricks_of(dense, n, offset);
  const Mat4 world_to_index = glm::translate(Mat4(1.0f), Vec3(offset) + Vec3(0.3f, -2.0f, 1.0f)) *
                              glm::rotate(Mat4(1.0f), 0.7f, glm::normalize(Vec3(1.0f, 2.0f, 3.0f))) *
                              glm::scale(Mat4(1.0f), Vec3(9.0f, 7.0f, 11.0f));
  const VolumeGrid grid(1, world_to_index, b.origins, b.values);
  EXPECT_LT(grid.bricks(), size_t(3 * 2 * 4));
  const Mat4 index_to_world = glm::inverse(world_to_index);
  double worst = 0.0;
  for (int i = 0; i < 20000; ++i) {
    // Index points over the volume and a voxel beyond it on each side.
    const Vec3 p(u(gen) * float(n.x + 2) - 1.5f, u(gen) * float(n.y + 2) - 1.5f, u(gen) * float(n.z + 2) - 1.5f);
    const Vec3 world = Vec3(index_to_world * glm::vec4(p + Vec3(offset), 1.0f));
    const glm::vec4 got = grid.lookup(world);
    const float want = dense_trilinear(dense, n, p);
    worst = std::max(worst, double(std::abs(got.x - want)));
    ASSERT_EQ(got.x, got.y);
    ASSERT_EQ(got.w, 1.0f);
    // The brick's bound holds every lookup in it.
    ASSERT_LE(got.x, grid.brick_max(world) + 1e-6f) << "at " << p.x << " " << p.y << " " << p.z;
  }
  std::printf("largest difference from the dense trilinear reference: %.3g\n", worst);
  EXPECT_LT(worst, 2e-4) << "largest difference from the dense trilinear reference";
}

TEST(VolumeGrid, EmptyGridsAndNanVoxelsGiveFiniteValues) {
  const VolumeGrid empty(1, Mat4(1.0f), {}, {});
  EXPECT_EQ(empty.lookup(Vec3(0.5f)).x, 0.0f);
  EXPECT_EQ(empty.brick_max(Vec3(0.5f)), 0.0f);
  EXPECT_TRUE(empty.brick_centres().empty());
  std::vector<float> values(size_t(VolumeGrid::kBrickVoxels) * 3, 1.0f);
  values[0] = std::numeric_limits<float>::quiet_NaN();
  values[5] = std::numeric_limits<float>::infinity();
  values[100] = -std::numeric_limits<float>::infinity();
  const VolumeGrid grid(3, Mat4(1.0f), {glm::ivec3(0)}, values);
  for (const Vec3 p : {Vec3(0.0f), Vec3(0.5f, 0.2f, 0.1f), Vec3(1.7f, 10.0f, 0.3f), Vec3(1e30f), Vec3(-1e30f),
                       Vec3(std::numeric_limits<float>::quiet_NaN())}) {
    const glm::vec4 v = grid.lookup(p);
    for (int c = 0; c < 4; ++c) EXPECT_TRUE(std::isfinite(v[c])) << p.x;
    EXPECT_TRUE(std::isfinite(grid.brick_max(p)));
  }
  EXPECT_EQ(grid.lookup(Vec3(0.0f)).x, 0.0f);  // the NaN voxel, read as 0
  EXPECT_THROW(VolumeGrid(1, Mat4(0.0f), {}, {}), std::invalid_argument);
  EXPECT_THROW(VolumeGrid(1, Mat4(1.0f), {glm::ivec3(3, 0, 0)}, std::vector<float>(512)), std::invalid_argument);
  EXPECT_THROW(VolumeGrid(1, Mat4(1.0f), {glm::ivec3(0), glm::ivec3(0)}, std::vector<float>(1024)),
               std::invalid_argument);
  EXPECT_THROW(VolumeGrid(5, Mat4(1.0f), {}, {}), std::invalid_argument);
}

// A clip box (Cycles 3.4's dense textures end at the active bounding box): lookups inside it
// unchanged, outside it 0, and a box with lo > hi refused.
TEST(VolumeGrid, ClipBoxZeroesLookupsOutsideIt) {
  VolumeGrid grid(1, Mat4(1.0f), {glm::ivec3(0)}, std::vector<float>(size_t(VolumeGrid::kBrickVoxels), 1.0f));
  EXPECT_FLOAT_EQ(grid.lookup(Vec3(7.3f, 3.0f, 3.0f)).x, 0.7f);  // fading past the last voxel centre
  grid.clip(Vec3(-0.5f), Vec3(7.5f));
  EXPECT_FLOAT_EQ(grid.lookup(Vec3(7.4f, 3.0f, 3.0f)).x, 0.6f);
  EXPECT_EQ(grid.lookup(Vec3(7.6f, 3.0f, 3.0f)).x, 0.0f);
  EXPECT_EQ(grid.lookup(Vec3(3.0f, -0.6f, 3.0f)).x, 0.0f);
  EXPECT_EQ(grid.lookup(Vec3(3.0f, 3.0f, 3.0f)).x, 1.0f);
  EXPECT_THROW(grid.clip(Vec3(1.0f), Vec3(0.0f)), std::invalid_argument);
}

// Ratio tracking's transmittance across a box of bricks of constant density, read by a volume
// program (Geometry > Position -> VolumeGrid as the absorption), against exp(-sigma d).
TEST(VolumeGrid, TransmittanceThroughAConstantBoxIsBeerLambert) {
  const float sigma = 2.0f;
  // 2 x 2 x 2 bricks (16^3 voxels) at 10 voxels per metre: constant over index [0, 15], world [0, 1.5].
  std::vector<glm::ivec3> origins;
  for (int i = 0; i < 8; ++i) origins.push_back(glm::ivec3(i & 1, (i >> 1) & 1, i >> 2) * B);
  Scene scene;
  const uint32_t material = scene.add_material(Material{});
  const uint32_t id = scene.add_volume_grid(VolumeGrid(1, glm::scale(Mat4(1.0f), Vec3(10.0f)), origins,
                                                       std::vector<float>(8 * size_t(VolumeGrid::kBrickVoxels), sigma)));
  ShaderInstruction position;
  position.op = ShaderOpcode::Geometry;
  position.out = 0;
  ShaderInstruction lookup;
  lookup.op = ShaderOpcode::VolumeGrid;
  lookup.resource = int32_t(id);
  lookup.in[0] = 0;
  lookup.out = 1;
  VaryingMedium medium;
  medium.program = scene.add_shader_program(ShaderProgram({}, {position, lookup}, 2, 0));
  medium.sigma_a = 1;
  medium.bounds_min = Vec3(0.0f);
  medium.bounds_max = Vec3(1.5f);
  scene.set_material_volume(material, medium, true);
  const int32_t varying = scene.media().varying_index(scene.media().of(material));
  const VaryingMedium& set = scene.media().varying(varying);
  EXPECT_GE(set.majorant, sigma);
  MediumMix mix;
  mix.add_varying(varying, set.majorant);
  const int runs = 40000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < runs; ++i) {
    Rng rng(uint32_t(i), 17u, 3u);
    const float t = ratio_tracking(scene, mix, Vec3(0.75f, 0.75f, -1.0f), Vec3(0.0f, 0.0f, 1.0f), 4.0f, rng).x;
    sum += t;
    sum2 += double(t) * t;
  }
  const double mean = sum / runs, error = std::sqrt((sum2 / runs - mean * mean) / runs);
  const double want = std::exp(-double(sigma) * 1.5);
  std::printf("ratio tracking %.5f +- %.5f, exp(-sigma d) %.5f, majorant %.3f\n", mean, error, want,
              double(set.majorant));
  EXPECT_NEAR(mean, want, 4.0 * error + 1e-4) << "standard error " << error;
}

}  // namespace
}  // namespace torrance
