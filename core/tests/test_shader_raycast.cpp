// The Raycast node's op (shader_raycast.h, Cycles 5.3's svm_node_raycast) against closed forms:
// a floor square at z = 0 (its smooth normals tilted, so that Hit Normal tells the smooth normal
// from the flat one) under a shelf square at z = 2 from which the ray leaves: Is Hit, Self Hit,
// Hit Distance (in lengths of the unnormalised Direction), Hit Position and Hit Normal; a miss;
// a Length short of the floor; the shelf's own triangle passed by only for a ray from exactly the
// hit; the floor's back turning the normal; Only Local; no scene to trace; and rays leaving a
// tilted shelf at a glancing angle.
#include "torrance/scene/scene.h"
#include "torrance/shader/shader_raycast.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include <xmmintrin.h>

namespace torrance {
namespace {

// The floor's corner normals: all leaning toward +x by the same angle (unit).
const Vec3 kFloorSmooth = glm::normalize(Vec3(0.3f, 0.0f, 1.0f));

// A square of half-width `half` at height z facing +z (two triangles), every corner normal `smooth`.
uint32_t add_square(Scene& scene, float z, const Vec3& smooth, float half = 1.0f) {
  std::vector<float> pos;
  for (float y : {-half, half})
    for (float x : {-half, half}) pos.insert(pos.end(), {x, y, z});
  const std::vector<int64_t> tris{0, 1, 3, 0, 3, 2};
  std::vector<float> normals;
  for (int k = 0; k < 6; ++k) normals.insert(normals.end(), {smooth.x, smooth.y, smooth.z});
  return scene.add_mesh(pos.data(), 4, tris.data(), 2, normals.data(), nullptr);
}

// A program of one Raycast instruction over constant inputs (Only Local: the scene then builds
// the objects' own BVHs).
ShaderProgram raycast_program(const Vec3& position, const Vec3& direction, float length, int mode, bool local,
                              float bump_width = 0.0f) {
  ShaderInstruction ins;
  ins.op = ShaderOpcode::Raycast;
  ins.mode = uint8_t(mode);
  ins.flags = local ? shader::kRaycastOnlyLocal : 0;
  ins.in = {0, 1, 2, 3};
  ins.out = 4;
  return ShaderProgram({glm::vec4(position, 0.0f), glm::vec4(direction, 0.0f), glm::vec4(length),
                        glm::vec4(bump_width)},
                       {ins}, 5, 0);
}

// Denormals flushed to zero (FTZ and DAZ), as the render's threads run (integrator.cpp): the
// float just past 0 then reads as 0.
struct FlushDenormals {
  unsigned saved = _mm_getcsr();
  FlushDenormals() { _mm_setcsr(saved | 0x8040u); }
  ~FlushDenormals() { _mm_setcsr(saved); }
};

class RaycastNode : public ::testing::Test {
 protected:
  void SetUp() override {
    scene.add_material(Material{});
    floor = add_square(scene, 0.0f, kFloorSmooth);
    shelf = add_square(scene, 2.0f, Vec3(0, 0, 1));
    scene.add_shader_program(raycast_program(Vec3(0.0f), Vec3(0.0f), 1.0f, 0, true));
    scene.commit();
    // The shading point: where a ray from above meets the shelf, as the path tracer finds it.
    Ray down;
    down.origin = Vec3(0.2f, 0.1f, 5.0f);
    down.dir = Vec3(0, 0, -1);
    SurfaceHit hit;
    EXPECT_TRUE(scene.intersect(down, hit));
    EXPECT_EQ(hit.object, shelf);
    g.tracer = &scene;
    g.object = hit.object;
    g.prim = hit.prim;
    g.position = hit.position;
    g.normal = g.true_normal = Vec3(0, 0, 1);
  }
  // The op's register for the node's output `mode` (0: Is Hit, Self Hit, Hit Distance; 1: Hit
  // Position; 2: Hit Normal).
  glm::vec4 run(const Vec3& position, const Vec3& direction, float length, int mode, bool local = false,
                float bump_width = 0.0f) const {
    const ShaderProgram p = raycast_program(position, direction, length, mode, local, bump_width);
    std::array<glm::vec4, 5> regs{};
    p.run(g, {}, regs.data());
    return regs[4];
  }
  Scene scene;
  uint32_t floor = 0, shelf = 0;
  ShaderGlobals g;
};

void expect_near(const glm::vec4& got, const glm::vec4& want, float tolerance = 1e-5f) {
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(got[k], want[k], tolerance) << "lane " << k;
}

TEST_F(RaycastNode, HitsTheFloorFromTheShelf) {
  const Vec3 down(0, 0, -1);
  expect_near(run(g.position, down, 10.0f, 0), glm::vec4(1.0f, 0.0f, 2.0f, 0.0f));
  expect_near(run(g.position, down, 10.0f, 1), glm::vec4(0.2f, 0.1f, 0.0f, 0.0f));
  expect_near(run(g.position, down, 10.0f, 2), glm::vec4(kFloorSmooth, 0.0f));  // smooth, facing the ray
  // Distances in lengths of Direction, as Cycles (not normalised): half of them for a doubled one.
  expect_near(run(g.position, 2.0f * down, 10.0f, 0), glm::vec4(1.0f, 0.0f, 1.0f, 0.0f));
  expect_near(run(g.position, 2.0f * down, 10.0f, 1), glm::vec4(0.2f, 0.1f, 0.0f, 0.0f));
}

TEST_F(RaycastNode, MissesGiveLengthAndZeros) {
  expect_near(run(g.position, Vec3(0, 0, 1), 10.0f, 0), glm::vec4(0.0f, 0.0f, 10.0f, 0.0f));  // nothing above
  expect_near(run(g.position, Vec3(0, 0, 1), 10.0f, 1), glm::vec4(0.0f));
  expect_near(run(g.position, Vec3(0, 0, 1), 10.0f, 2), glm::vec4(0.0f));
  // A Length short of the floor: a miss, Hit Distance the Length.
  expect_near(run(g.position, Vec3(0, 0, -1), 1.5f, 0), glm::vec4(0.0f, 0.0f, 1.5f, 0.0f));
  expect_near(run(g.position, Vec3(0, 0, -1), 1.5f, 1), glm::vec4(0.0f));
  expect_near(run(g.position, Vec3(0, 0, -1), -1.0f, 0), glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
  expect_near(run(g.position, Vec3(0.0f), 10.0f, 0), glm::vec4(0.0f, 0.0f, 10.0f, 0.0f));  // no direction
  ShaderGlobals world = g;  // a world or light: nothing to trace (Cycles' object none)
  world.tracer = nullptr;
  const ShaderProgram p = raycast_program(g.position, Vec3(0, 0, -1), 10.0f, 0, false);
  std::array<glm::vec4, 5> regs{};
  p.run(world, {}, regs.data());
  expect_near(regs[4], glm::vec4(0.0f, 0.0f, 10.0f, 0.0f));
}

TEST_F(RaycastNode, SelfHitsOnlyFromOffTheHit) {
  // From exactly the hit the shelf's own triangle is passed by (met at t = 0 exactly: with
  // denormals flushed, as in a render, a restart one float past it would meet it again); from a
  // point above it, the shelf is met and is the hit's own object.
  expect_near(run(g.position, Vec3(0, 0, -1), 10.0f, 0), glm::vec4(1.0f, 0.0f, 2.0f, 0.0f));
  {
    FlushDenormals flushed;
    expect_near(run(g.position, Vec3(0, 0, -1), 10.0f, 0), glm::vec4(1.0f, 0.0f, 2.0f, 0.0f));
  }
  const Vec3 above = g.position + Vec3(0.0f, 0.0f, 0.5f);
  expect_near(run(above, Vec3(0, 0, -1), 10.0f, 0), glm::vec4(1.0f, 1.0f, 0.5f, 0.0f));
  expect_near(run(above, Vec3(0, 0, -1), 10.0f, 2), glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));
  // At a bump's offset hit nothing is skipped, the ray starting 1.1 filter widths of the
  // differential away: the shelf 0.5 below is met, and not when the start lies past it.
  ShaderGlobals offset = g;
  offset.dpdx = offset.dpdy = Vec3(0.1f, 0.0f, 0.0f);  // Cycles' dP: 0.1
  const ShaderProgram near = raycast_program(above, Vec3(0, 0, -1), 10.0f, 0, false, 1.0f);
  const ShaderProgram far = raycast_program(above, Vec3(0, 0, -1), 10.0f, 0, false, 5.0f);
  std::array<glm::vec4, 5> regs{};
  near.run(offset, {}, regs.data());
  expect_near(regs[4], glm::vec4(1.0f, 1.0f, 0.5f, 0.0f));
  far.run(offset, {}, regs.data());
  expect_near(regs[4], glm::vec4(1.0f, 0.0f, 2.5f, 0.0f));
}

TEST_F(RaycastNode, BackFacesTurnTheNormalToTheRay) {
  const Vec3 below(0.2f, 0.1f, -1.0f);
  expect_near(run(below, Vec3(0, 0, 1), 10.0f, 0), glm::vec4(1.0f, 0.0f, 1.0f, 0.0f));
  expect_near(run(below, Vec3(0, 0, 1), 10.0f, 2), glm::vec4(-kFloorSmooth, 0.0f));
}

TEST_F(RaycastNode, OnlyLocalSeesTheHitsObject) {
  const Vec3 top(0.2f, 0.1f, 5.0f), down(0, 0, -1);
  expect_near(run(top, down, 10.0f, 0), glm::vec4(1.0f, 1.0f, 3.0f, 0.0f));  // the shelf, first
  ShaderGlobals on_floor = g;
  on_floor.object = floor;
  on_floor.position = Vec3(0.5f, 0.5f, 0.0f);
  const ShaderProgram p = raycast_program(top, down, 10.0f, 0, true);
  std::array<glm::vec4, 5> regs{};
  p.run(on_floor, {}, regs.data());
  expect_near(regs[4], glm::vec4(1.0f, 1.0f, 5.0f, 0.0f));  // through the shelf to the floor
  const ShaderProgram position = raycast_program(top, down, 10.0f, 1, true);
  position.run(on_floor, {}, regs.data());
  expect_near(regs[4], glm::vec4(0.2f, 0.1f, 0.0f, 0.0f));
  expect_near(run(g.position, down, 10.0f, 0, true), glm::vec4(0.0f, 0.0f, 10.0f, 0.0f));  // nothing under the shelf
}

// A tilted shelf (its corners not on float's grid) and rays leaving it at a glancing angle
// (cosine 0.1 to its plane): each passes by its own triangle, wherever rounding puts that hit,
// and meets the floor at the distance the planes give.
TEST(RaycastNodeGlancing, PassesItsOwnTriangle) {
  Scene scene;
  scene.add_material(Material{});
  add_square(scene, 0.0f, Vec3(0, 0, 1), 20.0f);
  const float c = std::cos(0.3f), s = std::sin(0.3f);
  std::vector<float> pos;
  for (float y : {-1.0f, 1.0f})
    for (float x : {-1.0f, 1.0f}) pos.insert(pos.end(), {x, c * y, 1.3f + s * y});
  const std::vector<int64_t> tris{0, 1, 3, 0, 3, 2};
  const uint32_t shelf = scene.add_mesh(pos.data(), 4, tris.data(), 2, nullptr, nullptr);
  scene.commit();
  const Vec3 n(0.0f, -s, c);  // the shelf's normal
  FlushDenormals flushed;
  int checked = 0;
  for (int i = 0; i < 64; ++i) {
    Ray down;
    down.origin = Vec3(-0.9f + 0.028f * float(i), 0.37f - 0.011f * float(i), 5.0f);
    down.dir = Vec3(0, 0, -1);
    SurfaceHit hit;
    ASSERT_TRUE(scene.intersect(down, hit));
    ASSERT_EQ(hit.object, shelf);
    ShaderGlobals g;
    g.tracer = &scene;
    g.object = hit.object;
    g.prim = hit.prim;
    g.position = hit.position;
    // Into the shelf's back at a glancing angle, toward the floor: t = z / -dir.z.
    const Vec3 dir = glm::normalize(Vec3(0.0f, 0.995f * c, 0.995f * s) * (i % 2 ? 1.0f : -1.0f) - 0.1f * n);
    if (!(dir.z < 0.0f)) continue;
    const ShaderProgram p = raycast_program(g.position, dir, 100.0f, 0, false);
    std::array<glm::vec4, 5> regs{};
    p.run(g, {}, regs.data());
    const float t = g.position.z / -dir.z;
    const Vec3 floor_point = g.position + t * dir;
    if (std::abs(floor_point.x) > 19.0f || std::abs(floor_point.y) > 19.0f) continue;  // off the floor
    expect_near(regs[4], glm::vec4(1.0f, 0.0f, t, 0.0f), 2e-4f);
    ++checked;
  }
  EXPECT_GT(checked, 16);
}

}  // namespace
}  // namespace torrance
