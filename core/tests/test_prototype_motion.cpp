// Motion blur of a deforming instanced mesh (Scene::set_prototype_motion): rays at a given time
// (ray_queries::set_time) against an instance of a prototype whose object-space vertices move
// hit where the prototype's positions interpolated at that time, placed by the instance's
// transform (or transform motion) at that time, say; the errors.
#include "scene/ray_queries.h"
#include "torrance/scene/scene.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace torrance {
namespace {

// The quad [-1, 1]^2 at z = 0, object space.
const float kQuad[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
const int64_t kTriangles[] = {0, 1, 2, 0, 2, 3};

// Three time steps of the quad: step s slid s m along +x and lifted z_s (0, 1, 1.5), so at time
// t its x offset is 2t and its height 2t before t = 0.5, t + 0.5 after.
std::vector<float> deforming_steps() {
  const float lift[] = {0.0f, 1.0f, 1.5f};
  std::vector<float> out;
  for (int s = 0; s < 3; ++s)
    for (int i = 0; i < 4; ++i) {
      out.push_back(kQuad[3 * i] + float(s));
      out.push_back(kQuad[3 * i + 1]);
      out.push_back(kQuad[3 * i + 2] + lift[s]);
    }
  return out;
}

float shift_at(float t) { return 2.0f * t; }
float lift_at(float t) { return t < 0.5f ? 2.0f * t : t + 0.5f; }

struct DeformingInstance {
  Scene scene;
  uint32_t prototype = 0;
  int64_t id = 0;
};

// One instance (scale 2, moved to (3, 0, 0.5)) of the quad, deforming by deforming_steps().
void make(DeformingInstance& d) {
  const int64_t m = d.scene.add_material(Material{});
  const int64_t slots[] = {0, 0}, table[] = {m};
  d.prototype = d.scene.add_prototype(kQuad, 4, kTriangles, 2, nullptr, slots);
  const float transform[] = {2, 0, 0, 3, 0, 2, 0, 0, 0, 0, 2, 0.5f};
  d.id = d.scene.add_instances(d.prototype, transform, 1, table, 1);
  const std::vector<float> steps = deforming_steps();
  d.scene.set_prototype_motion(d.prototype, 3, steps.data(), nullptr);
}

// The hit of a ray straight down through (x, y) at time t, or nullopt-like false.
bool hit_down(const Scene& scene, float x, float y, float t, SurfaceHit& hit) {
  ray_queries::set_time(t);
  Ray ray;
  ray.origin = Vec3(x, y, 20.0f);
  ray.dir = Vec3(0.0f, 0.0f, -1.0f);
  ray.tmin = 0.0f;
  ray.tmax = std::numeric_limits<float>::infinity();
  const bool found = scene.intersect(ray, hit);
  ray_queries::set_time(0.0f);
  return found;
}

TEST(PrototypeMotion, AHitAtTimeTIsOnTheInterpolatedPositions) {
  DeformingInstance d;
  make(d);
  d.scene.commit();
  EXPECT_TRUE(d.scene.has_motion());
  for (const float t : {0.0f, 0.2f, 0.5f, 0.7f, 1.0f}) {
    // The quad's object-space centre at time t, placed: (3 + 2 shift, 0, 0.5 + 2 lift).
    const float x = 3.0f + 2.0f * shift_at(t) + 0.3f, y = 0.4f;
    SurfaceHit hit;
    ASSERT_TRUE(hit_down(d.scene, x, y, t, hit)) << "t = " << t;
    EXPECT_NEAR(hit.position.z, 0.5f + 2.0f * lift_at(t), 1e-4f) << "t = " << t;
    EXPECT_NEAR(hit.position.x, x, 1e-4f);
    EXPECT_NEAR(hit.t, 20.0f - hit.position.z, 1e-3f);  // Embree's hit and the interpolated corners agree
    EXPECT_NEAR(hit.geometric_normal.z, 1.0f, 1e-5f);
    for (const Vec3& c : hit.corners) EXPECT_NEAR(c.z, hit.position.z, 1e-4f);
  }
  // Object-space x = 1.5 lies beyond the still quad's edge (1): covered once shifted by 0.5,
  // from t = 0.25 on.
  const float beyond = 3.0f + 2.0f * 1.5f;
  SurfaceHit hit;
  EXPECT_FALSE(hit_down(d.scene, beyond, 0.0f, 0.1f, hit));
  EXPECT_TRUE(hit_down(d.scene, beyond, 0.0f, 0.5f, hit));
}

TEST(PrototypeMotion, DeformationUnderTheInstancesTransformMotion) {
  DeformingInstance d;
  make(d);
  // The instance also slides 4 m along +y over the shutter.
  std::array<float, 24> motion = {2, 0, 0, 3, 0, 2, 0, 0, 0, 0, 2, 0.5f, 2, 0, 0, 3, 0, 2, 0, 4, 0, 0, 2, 0.5f};
  EXPECT_EQ(d.scene.set_instance_motion(&d.id, 1, 2, motion.data()), 0u);
  d.scene.commit();
  for (const float t : {0.0f, 0.25f, 0.75f, 1.0f}) {
    const float x = 3.0f + 2.0f * shift_at(t) - 0.5f, y = 4.0f * t + 0.5f;
    SurfaceHit hit;
    ASSERT_TRUE(hit_down(d.scene, x, y, t, hit)) << "t = " << t;
    EXPECT_NEAR(hit.position.z, 0.5f + 2.0f * lift_at(t), 1e-4f) << "t = " << t;
  }
  // At t = 1 the quad's object-space y lies in [-1, 1] about world y = 4: world y = 1 is off it.
  SurfaceHit hit;
  EXPECT_FALSE(hit_down(d.scene, 3.0f + 4.0f, 1.0f, 1.0f, hit));
}

TEST(PrototypeMotion, InstancesOfAStillPrototypeAreUnchanged) {
  // A second prototype without motion beside the deforming one keeps its hits.
  DeformingInstance d;
  make(d);
  const int64_t table[] = {0}, slots[] = {0, 0};
  const uint32_t still = d.scene.add_prototype(kQuad, 4, kTriangles, 2, nullptr, slots);
  const float transform[] = {1, 0, 0, -5, 0, 1, 0, 0, 0, 0, 1, 0};
  d.scene.add_instances(still, transform, 1, table, 1);
  d.scene.commit();
  for (const float t : {0.0f, 1.0f}) {
    SurfaceHit hit;
    ASSERT_TRUE(hit_down(d.scene, -5.2f, 0.3f, t, hit));
    EXPECT_EQ(hit.position.z, 0.0f);
  }
}

TEST(PrototypeMotion, Errors) {
  DeformingInstance d;
  make(d);
  const std::vector<float> steps = deforming_steps();
  EXPECT_THROW(d.scene.set_prototype_motion(7, 3, steps.data(), nullptr), std::invalid_argument);
  EXPECT_THROW(d.scene.set_prototype_motion(d.prototype, 1, steps.data(), nullptr), std::invalid_argument);
  std::vector<float> bad = steps;
  bad[13] = std::nanf("");
  EXPECT_THROW(d.scene.set_prototype_motion(d.prototype, 3, bad.data(), nullptr), std::invalid_argument);
  // A step 1e6 m away, under a transform of scale 1e7: beyond 1e12, refused and forgotten.
  Scene far;
  const int64_t slots[] = {0, 0}, table[] = {far.add_material(Material{})};
  const uint32_t p = far.add_prototype(kQuad, 4, kTriangles, 2, nullptr, slots);
  const float big[] = {1e7f, 0, 0, 0, 0, 1e7f, 0, 0, 0, 0, 1e7f, 0};
  far.add_instances(p, big, 1, table, 1);
  std::vector<float> away(kQuad, kQuad + 12);
  away.insert(away.end(), kQuad, kQuad + 12);
  away[12] = 1e6f;
  EXPECT_THROW(far.set_prototype_motion(p, 2, away.data(), nullptr), std::invalid_argument);
  EXPECT_FALSE(far.has_motion());
  // ... and the next instance is checked against the still bounds again: it is accepted.
  const float fine[] = {1e10f, 0, 0, 0, 0, 1e10f, 0, 0, 0, 0, 1e10f, 0};
  EXPECT_NO_THROW(far.add_instances(p, fine, 1, table, 1));
}

}  // namespace
}  // namespace torrance
