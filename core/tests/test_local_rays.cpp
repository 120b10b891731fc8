// Local ray queries (ShaderTracer::local_hits, local_occluded: Cycles' scene_intersect_local) and
// the Bevel op that traces them: rays see the named object's own triangles only (a world-space
// mesh, or an instance's prototype placed by its transform), every hit along the ray counted and
// at most max_hits of them kept; a scene whose programs trace no local rays answers none.
#include "torrance/scene/scene.h"
#include "torrance/shader/shader_bevel.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace torrance {
namespace {

constexpr uint32_t kInstanceBit = 0x80000000u;

// A 2 x 2 square at height z (two triangles, facing +z).
void add_square(std::vector<float>& pos, std::vector<int64_t>& tris, float z) {
  const int64_t base = int64_t(pos.size() / 3);
  for (float y : {-1.0f, 1.0f})
    for (float x : {-1.0f, 1.0f}) pos.insert(pos.end(), {x, y, z});
  tris.insert(tris.end(), {base, base + 1, base + 3, base, base + 3, base + 2});
}

uint32_t add_mesh(Scene& scene, const std::vector<float>& pos, const std::vector<int64_t>& tris) {
  return scene.add_mesh(pos.data(), pos.size() / 3, tris.data(), tris.size() / 3, nullptr, nullptr);
}

// One mesh of squares at the given heights (the scene's first material added if it has none).
uint32_t add_squares(Scene& scene, const std::vector<float>& heights) {
  if (scene.num_materials() == 0) scene.add_material(Material{});
  std::vector<float> pos;
  std::vector<int64_t> tris;
  for (float z : heights) add_square(pos, tris, z);
  return add_mesh(scene, pos, tris);
}

// A program with a Bevel instruction: the scene then builds the objects' own BVHs.
ShaderProgram bevel_program() {
  ShaderInstruction ins;
  ins.op = ShaderOpcode::Bevel;
  ins.in = {0, 1, 2};
  ins.out = 3;
  return ShaderProgram({glm::vec4(0.1f), glm::vec4(0, 0, 1, 0), glm::vec4(4.0f)}, {ins}, 4, 0);
}

TEST(LocalRays, SeeTheirOwnObjectOnly) {
  Scene scene;
  const uint32_t a = add_squares(scene, {0.0f}), b = add_squares(scene, {0.5f});
  scene.add_shader_program(bevel_program());
  scene.commit();
  const Vec3 origin(0.2f, 0.1f, 1.0f), down(0.0f, 0.0f, -1.0f);
  LocalHit hits[4];
  ASSERT_EQ(scene.local_hits(a, origin, down, 2.0f, 1u, hits, 4), 1);
  EXPECT_NEAR(hits[0].position.z, 0.0f, 1e-6f);
  EXPECT_NEAR(hits[0].position.x, 0.2f, 1e-6f);
  EXPECT_NEAR(hits[0].true_normal.z, 1.0f, 1e-6f);
  ASSERT_EQ(scene.local_hits(b, origin, down, 2.0f, 1u, hits, 4), 1);
  EXPECT_NEAR(hits[0].position.z, 0.5f, 1e-6f);
  // The segment ends above a: b alone occludes it, a (locally) does not.
  EXPECT_TRUE(scene.local_occluded(b, origin, down, 0.0f, 0.75f));
  EXPECT_FALSE(scene.local_occluded(a, origin, down, 0.0f, 0.75f));
  EXPECT_TRUE(scene.local_occluded(a, origin, down, 0.0f, 1.5f));
  EXPECT_FALSE(scene.local_occluded(ShaderGlobals::kNoObject, origin, down, 0.0f, 1.5f));
}

TEST(LocalRays, CountEveryHitAndKeepAFew) {
  Scene scene;
  std::vector<float> heights;
  for (int k = 0; k < 10; ++k) heights.push_back(0.1f * float(k));
  const uint32_t stack = add_squares(scene, heights);
  scene.add_shader_program(bevel_program());
  scene.commit();
  LocalHit hits[4];
  EXPECT_EQ(scene.local_hits(stack, Vec3(0.3f, -0.2f, 2.0f), Vec3(0, 0, -1), 3.0f, 7u, hits, 4), 10);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < i; ++j) EXPECT_NE(hits[i].position.z, hits[j].position.z);
}

TEST(LocalRays, InstancesTraceTheirPlacedPrototype) {
  Scene scene;
  scene.add_material(Material{});
  std::vector<float> pos;
  std::vector<int64_t> tris;
  add_square(pos, tris, 0.0f);
  scene.add_prototype(pos.data(), pos.size() / 3, tris.data(), tris.size() / 3, nullptr, nullptr);
  // Two instances: turned upside down (mirrored in z) at height 1, and scaled at height 3.
  const std::array<float, 24> transforms{1, 0, 0, 0.5f, 0, 1, 0, 0, 0, 0, -1, 1,
                                         2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 3};
  const int64_t table[] = {0};
  const uint32_t first = scene.add_instances(0, transforms.data(), 2, table, 1);
  scene.add_shader_program(bevel_program());
  scene.commit();
  const Vec3 origin(0.9f, 0.3f, 5.0f), down(0, 0, -1);
  LocalHit hits[4];
  ASSERT_EQ(scene.local_hits(first | kInstanceBit, origin, down, 10.0f, 3u, hits, 4), 1);
  EXPECT_NEAR(hits[0].position.z, 1.0f, 1e-5f);
  EXPECT_NEAR(hits[0].true_normal.z, -1.0f, 1e-5f);  // the mirrored square faces down
  ASSERT_EQ(scene.local_hits((first + 1) | kInstanceBit, origin, down, 10.0f, 3u, hits, 4), 1);
  EXPECT_NEAR(hits[0].position.z, 3.0f, 1e-5f);
  // The same hit as the scene's own tracing finds.
  Ray ray;
  ray.origin = origin;
  ray.dir = down;
  ray.tmin = 0.0f;
  ray.tmax = 1e30f;
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(ray, hit));
  EXPECT_NEAR(glm::length(hit.position - hits[0].position), 0.0f, 1e-5f);
  EXPECT_EQ(hit.object, (first + 1) | kInstanceBit);
}

TEST(LocalRays, NoneWithoutAProgramThatTracesThem) {
  Scene scene;
  const uint32_t a = add_squares(scene, {0.0f});
  scene.commit();
  LocalHit hits[4];
  EXPECT_EQ(scene.local_hits(a, Vec3(0, 0, 1), Vec3(0, 0, -1), 2.0f, 1u, hits, 4), 0);
}

// A unit cube, flat faces: at the middle of an edge the bevelled normal leans halfway between
// the two faces'; in the middle of a face it is the face's.
TEST(LocalRays, BevelRoundsACubesEdge) {
  Scene scene;
  scene.add_material(Material{});
  const std::vector<float> pos{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
  const std::vector<int64_t> tris{0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                  2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  const uint32_t cube = add_mesh(scene, pos, tris);
  scene.add_shader_program(bevel_program());
  scene.commit();
  ShaderGlobals g;
  g.tracer = &scene;
  g.object = cube;
  g.normal = g.true_normal = Vec3(0, 0, 1);
  g.incoming = glm::normalize(Vec3(0.1f, -0.2f, 1.0f));
  g.position = Vec3(0.4f, 0.5f, 1.0f);  // the top face's middle
  const Vec3 flat = shader::bevel_normal(g, 0.1f, 64);
  EXPECT_NEAR(flat.z, 1.0f, 1e-4f);
  g.position = Vec3(1.0f, 0.5f, 1.0f);  // on the edge to the +x face
  const Vec3 edge = shader::bevel_normal(g, 0.1f, 256);
  EXPECT_NEAR(edge.y, 0.0f, 0.05f);
  EXPECT_NEAR(std::atan2(edge.x, edge.z), 0.25f * kPi, 0.12f);
  g.position = Vec3(0.95f, 0.5f, 1.0f);  // inside the radius: leaning less
  const Vec3 near_edge = shader::bevel_normal(g, 0.1f, 256);
  EXPECT_GT(near_edge.x, 0.05f);
  EXPECT_LT(near_edge.x, edge.x);
  EXPECT_EQ(shader::bevel_normal(g, 0.0f, 8), g.normal);  // no radius: the normal
  g.path.diffuse_depth = 1;                                // after a diffuse bounce: as Cycles
  EXPECT_EQ(shader::bevel_normal(g, 0.1f, 8), g.normal);
}

}  // namespace
}  // namespace torrance
