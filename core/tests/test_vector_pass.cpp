// The Vector pass (kPassVector, film/motion_vectors.h) on closed forms: an orthographic camera
// 4 m wide over 64 pixels (16 px per metre) looks straight down at a quad; a mesh, an instance, a
// deforming instance or the camera moved between the neighbouring frames gives interior pixels
// exactly (previous - now, now - next) in pixels with y up, the sky 0; without the camera's
// neighbouring frames the pass is 0 (Cycles under motion blur).
#include "torrance/integrator/integrator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <utility>

namespace torrance {
namespace {

constexpr int kSize = 64;
constexpr float kPixelsPerMetre = 16.0f;

std::array<float, 16> translation(float x, float y, float z) {
  return {1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z, 0, 0, 0, 1};
}

void look_down_orthographic(Scene& scene) {
  CameraParams cam;
  cam.camera_to_world = translation(0.0f, 0.0f, 10.0f);  // looks down -Z, +X right, +Y up
  cam.type = CameraType::Orthographic;
  cam.ortho_scale = 4.0f;
  scene.set_camera(cam);
}

// The quad [-1, 1]^2 at z = 0 (2 m: 32 pixels across the frame's centre).
const float kQuad[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
const int64_t kTriangles[] = {0, 1, 2, 0, 2, 3};

// The quad as a world-space mesh of a default material; its mesh id.
uint32_t add_quad_mesh(Scene& scene) {
  const int64_t m = scene.add_material(Material{});
  const int64_t mats[] = {m, m};
  return scene.add_mesh(kQuad, 4, kTriangles, 2, nullptr, mats);
}

RenderSettings vector_render() {
  RenderSettings s;
  s.width = s.height = kSize;
  s.samples = 4;
  s.max_bounces = 0;
  s.passes = kPassVector;
  return s;
}

const Image& vector_pass(const RenderResult& r) {
  const auto it = std::find_if(r.passes.begin(), r.passes.end(), [](const auto& p) { return p.first == "Vector"; });
  if (it == r.passes.end()) throw std::runtime_error("no Vector pass");
  return it->second;
}

// Every pixel of the quad's inner 24 x 24 (the frame's centre) holds `inside`, every pixel 4 or
// more beyond its edge 0.
void expect_vectors(const RenderResult& r, const glm::vec4& inside) {
  const Image& v = vector_pass(r);
  ASSERT_EQ(v.channels, 4);
  int checked_inside = 0, checked_sky = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float* p = &v.rgba[(size_t(y) * kSize + x) * 4];
      const int dx = std::abs(2 * x + 1 - kSize), dy = std::abs(2 * y + 1 - kSize);  // twice the distance
      if (dx <= 24 && dy <= 24) {
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(p[c], inside[c], 1e-3f) << "pixel " << x << ", " << y << " channel " << c;
        ++checked_inside;
      } else if (dx >= 40 || dy >= 40) {
        for (int c = 0; c < 4; ++c) EXPECT_EQ(p[c], 0.0f) << "sky pixel " << x << ", " << y;
        ++checked_sky;
      }
    }
  EXPECT_GT(checked_inside, 100);
  EXPECT_GT(checked_sky, 100);
}

// The quad's vertices one frame before, 0.5 m to the left (-X), and one after, 0.5 m right and
// 0.25 m up (+Y).
std::pair<std::array<float, 12>, std::array<float, 12>> shifted_quads() {
  std::array<float, 12> before, after;
  for (int i = 0; i < 4; ++i) {
    for (int c = 0; c < 3; ++c) before[3 * i + c] = after[3 * i + c] = kQuad[3 * i + c];
    before[3 * i] -= 0.5f;
    after[3 * i] += 0.5f;
    after[3 * i + 1] += 0.25f;
  }
  return {before, after};
}

TEST(VectorPass, AMovingMeshInPixelsYUp) {
  Scene scene;
  const uint32_t mesh = add_quad_mesh(scene);
  look_down_orthographic(scene);
  scene.set_frame_motion_camera(translation(0, 0, 10), translation(0, 0, 10));
  const auto [before, after] = shifted_quads();
  scene.set_frame_motion_mesh(mesh, before.data(), after.data());
  const RenderResult r = render(scene, vector_render());
  expect_vectors(r, glm::vec4(-0.5f, 0.0f, -0.5f, -0.25f) * kPixelsPerMetre);
}

TEST(VectorPass, AMovingInstanceAndAMovingCamera) {
  Scene scene;
  const uint32_t m = scene.add_material(Material{});
  const int64_t slots[] = {0, 0}, table[] = {m};
  const uint32_t proto = scene.add_prototype(kQuad, 4, kTriangles, 2, nullptr, slots);
  const float now[] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  const int64_t id = scene.add_instances(proto, now, 1, table, 1);
  look_down_orthographic(scene);
  // The instance a quarter turn about Z before (a point at (x, y) was at (-y, x)) and 0.5 m
  // down after; the camera 0.25 m right before and after.
  const float before[] = {0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0};
  const float after[] = {1, 0, 0, 0, 0, 1, 0, -0.5f, 0, 0, 1, 0};
  scene.set_frame_motion_instances(&id, 1, before, after);
  scene.set_frame_motion_camera(translation(0.25f, 0, 10), translation(0.25f, 0, 10));
  RenderSettings settings = vector_render();
  settings.samples = 256;  // the turn's vectors vary over a pixel: its samples' mean position
  const RenderResult r = render(scene, settings);
  // The turn's vectors vary over the quad: checked at the four pixels about its centre (0, 0),
  // which the turn did not move (the camera's 0.25 m aside did), within the spread of their
  // samples' mean positions.
  const Image& v = vector_pass(r);
  glm::vec4 centre(0.0f);
  for (int y = kSize / 2 - 1; y <= kSize / 2; ++y)
    for (int x = kSize / 2 - 1; x <= kSize / 2; ++x)
      for (int c = 0; c < 4; ++c) centre[c] += 0.25f * v.rgba[(size_t(y) * kSize + x) * 4 + size_t(c)];
  const glm::vec4 expected = glm::vec4(-0.25f, 0.0f, 0.25f, 0.5f) * kPixelsPerMetre;
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(centre[c], expected[c], c < 2 ? 0.15f : 1e-3f) << "channel " << c;
  // A pixel at (x, y) metres: the turn moved it from (-y, x) (the camera's 0.25 m aside).
  const int px = kSize / 2 + 8, py = kSize / 2 + 4;  // pixel centre at (0.53125, -0.28125) m
  const float wx = (float(px) + 0.5f - kSize / 2) / kPixelsPerMetre, wy = -(float(py) + 0.5f - kSize / 2) / kPixelsPerMetre;
  const float* p = &v.rgba[(size_t(py) * kSize + px) * 4];
  EXPECT_NEAR(p[0], (-wy - 0.25f - wx) * kPixelsPerMetre, 0.15f);
  EXPECT_NEAR(p[1], (wx - wy) * kPixelsPerMetre, 0.15f);
  EXPECT_NEAR(p[2], 0.25f * kPixelsPerMetre, 1e-3f);
  EXPECT_NEAR(p[3], 0.5f * kPixelsPerMetre, 1e-3f);
}

TEST(VectorPass, ADeformingInstance) {
  // An instance (a quarter turn about Z: object (x, y) at world (-y, x)) of a prototype whose
  // vertices were 0.5 m along object -X one frame before and 0.5 m along +X, 0.25 m along +Y
  // one frame after: in world space 0.5 m along -Y before, (-0.25, 0.5) m after.
  Scene scene;
  const uint32_t m = scene.add_material(Material{});
  const int64_t slots[] = {0, 0}, table[] = {m};
  const uint32_t proto = scene.add_prototype(kQuad, 4, kTriangles, 2, nullptr, slots);
  const float turn[] = {0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0};
  const int64_t id = scene.add_instances(proto, turn, 1, table, 1);
  look_down_orthographic(scene);
  scene.set_frame_motion_camera(translation(0, 0, 10), translation(0, 0, 10));
  auto [before, after] = shifted_quads();
  scene.set_frame_motion_prototype(proto, before.data(), after.data());
  expect_vectors(render(scene, vector_render()), glm::vec4(0.0f, -0.5f, 0.25f, -0.5f) * kPixelsPerMetre);
  // The instance moving as well: 0.25 m along +X before, 0.5 m along -Y after, added to it.
  const float turn_before[] = {0, -1, 0, 0.25f, 1, 0, 0, 0, 0, 0, 1, 0};
  const float turn_after[] = {0, -1, 0, 0, 1, 0, 0, -0.5f, 0, 0, 1, 0};
  scene.set_frame_motion_instances(&id, 1, turn_before, turn_after);
  expect_vectors(render(scene, vector_render()), glm::vec4(0.25f, -0.5f, 0.25f, 0.0f) * kPixelsPerMetre);
  EXPECT_THROW(scene.set_frame_motion_prototype(proto + 1, before.data(), after.data()), std::invalid_argument);
  before[2] = std::nanf("");
  EXPECT_THROW(scene.set_frame_motion_prototype(proto, before.data(), after.data()), std::invalid_argument);
}

TEST(VectorPass, AMovingStrand) {
  Scene scene;
  scene.add_material(Material{});
  // A thick strand along y through the frame's centre, 0.5 m to the left before and 0.5 m
  // right and 0.25 m up after.
  const float keys[] = {0, -1.5f, 0, 0, -0.5f, 0, 0, 0.5f, 0, 0, 1.5f, 0};
  const float radii[] = {0.3f, 0.3f, 0.3f, 0.3f};
  const int64_t first[] = {0, 4};
  const uint32_t set = scene.add_curves(keys, radii, 4, first, 1, nullptr, CurveShape::Round);
  look_down_orthographic(scene);
  scene.set_frame_motion_camera(translation(0, 0, 10), translation(0, 0, 10));
  std::array<float, 12> before, after;
  for (int i = 0; i < 12; ++i) before[size_t(i)] = after[size_t(i)] = keys[i];
  for (int k = 0; k < 4; ++k) {
    before[size_t(3 * k)] -= 0.5f;
    after[size_t(3 * k)] += 0.5f;
    after[size_t(3 * k + 1)] += 0.25f;
  }
  scene.set_frame_motion_curves(set, first, 1, before.data(), after.data(), 4);
  const RenderResult r = render(scene, vector_render());
  const Image& v = vector_pass(r);
  const glm::vec4 expected = glm::vec4(-0.5f, 0.0f, -0.5f, -0.25f) * kPixelsPerMetre;
  int checked = 0;
  for (int y = 20; y < 44; ++y)  // the strand's middle segment, its 0.6 m (9.6 px) wide core
    for (int x = kSize / 2 - 2; x < kSize / 2 + 2; ++x) {
      for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(v.rgba[(size_t(y) * kSize + x) * 4 + size_t(c)], expected[c], 1e-3f) << x << ", " << y;
      ++checked;
    }
  EXPECT_EQ(checked, 96);
  const int64_t wrong[] = {0, 3};
  EXPECT_THROW(scene.set_frame_motion_curves(set, wrong, 1, before.data(), after.data(), 3), std::invalid_argument);
}

TEST(VectorPass, ZeroWithoutTheCamerasNeighbouringFrames) {
  Scene scene;
  const uint32_t mesh = add_quad_mesh(scene);
  look_down_orthographic(scene);
  std::array<float, 12> moved;
  for (int i = 0; i < 12; ++i) moved[size_t(i)] = kQuad[i] + (i % 3 == 0 ? 0.5f : 0.0f);
  scene.set_frame_motion_mesh(mesh, moved.data(), moved.data());
  expect_vectors(render(scene, vector_render()), glm::vec4(0.0f));
}

TEST(VectorPass, BadNeighbouringFramesAreRejected) {
  Scene scene;
  const uint32_t mesh = add_quad_mesh(scene);
  std::array<float, 12> bad;
  std::copy(std::begin(kQuad), std::end(kQuad), bad.begin());
  bad[4] = std::nanf("");
  EXPECT_THROW(scene.set_frame_motion_mesh(mesh, bad.data(), kQuad), std::invalid_argument);
  EXPECT_THROW(scene.set_frame_motion_mesh(mesh + 1, kQuad, kQuad), std::invalid_argument);
  std::array<float, 16> camera = translation(0, 0, 10);
  camera[3] = INFINITY;
  EXPECT_THROW(scene.set_frame_motion_camera(camera, translation(0, 0, 10)), std::invalid_argument);
  const int64_t unknown = 3;
  const float identity[] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  EXPECT_THROW(scene.set_frame_motion_instances(&unknown, 1, identity, identity), std::invalid_argument);
}

}  // namespace
}  // namespace torrance
