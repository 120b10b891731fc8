// Glass rendered end to end: a glass sphere in a white furnace, the closed form of a smooth slab at
// normal incidence, lights seen through rough glass (NEE on the far side), and no NaN/Inf.
#include "torrance/integrator/integrator.h"
#include "torrance/bsdfs/material_bsdf.h"

#include "scene_helpers.h"

#include <gtest/gtest.h>

#include <vector>

namespace torrance {
namespace {

using test::add_quad;
using test::look_down;
using test::mean_rgb;

// A UV sphere (smooth corner normals) of the given material index.
void add_sphere(Scene& scene, const Vec3& centre, float radius, int64_t material, int rings = 48, int segments = 96) {
  std::vector<float> p;
  std::vector<int64_t> tris, mats;
  std::vector<float> normals;
  auto vertex = [&](int i, int j) {
    const float theta = kPi * float(i) / float(rings), phi = kTwoPi * float(j) / float(segments);
    return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  };
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= segments; ++j) {
      const Vec3 v = centre + radius * vertex(i, j);
      p.insert(p.end(), {v.x, v.y, v.z});
    }
  auto id = [&](int i, int j) { return int64_t(i * (segments + 1) + j); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const int64_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      for (auto tri : {std::array<int64_t, 3>{a, b, c}, std::array<int64_t, 3>{a, c, d}}) {
        if (tri[0] == tri[1] || tri[1] == tri[2]) continue;
        tris.insert(tris.end(), tri.begin(), tri.end());
        for (int64_t v : tri) {
          const Vec3 n = glm::normalize(Vec3(p[3 * v], p[3 * v + 1], p[3 * v + 2]) - centre);
          normals.insert(normals.end(), {n.x, n.y, n.z});
        }
        mats.push_back(material);
      }
    }
  scene.add_mesh(p.data(), p.size() / 3, tris.data(), tris.size() / 3, normals.data(), mats.data());
}

Material glass(float roughness, float ior = 1.5f) {
  Material m;
  m.base_color = Vec3(1.0f);
  m.roughness = roughness;
  m.transmission = 1.0f;
  m.ior = ior;
  return m;
}

RenderSettings settings(int size, int samples, int bounces) {
  return test::square_render(size, samples, bounces, BrdfModel::Principled);
}

// A smooth glass sphere under a uniform white world: F + (1 - F) = 1 at every interface, so every
// pixel (sphere and background alike) is the world's radiance; a rough one loses only what Cycles
// 3.4's split loses (at most a few per cent here) and never gains.
TEST(GlassRender, WhiteFurnaceGlassSphereStaysOne) {
  for (float roughness : {0.0f, 0.3f}) {
    Scene scene;
    const uint32_t m = scene.add_material(glass(roughness));
    add_sphere(scene, Vec3(0.0f), 1.0f, m);
    scene.lights().set_world(Vec3(1.0f), 1.0f);
    look_down(scene, 6.0f, 120.0f);  // the sphere fills most of the frame
    const RenderResult r = render(scene, settings(24, 128, 64));
    EXPECT_EQ(r.nonfinite_samples, 0u);
    const float mean = mean_rgb(r.image).g;
    std::printf("furnace glass sphere r=%.1f: mean %.4f\n", roughness, mean);
    if (roughness == 0.0f) EXPECT_NEAR(mean, 1.0f, 0.01f);
    else {
      EXPECT_LE(mean, 1.0f + 0.01f);
      EXPECT_GT(mean, 0.9f);
    }
    for (size_t i = 0; i < r.image.rgba.size(); ++i) ASSERT_LE(r.image.rgba[i], roughness == 0.0f ? 1.1f : 1.2f);
  }
}

// A smooth pane between the camera and an emitter, seen at normal incidence: the light crossing it
// is (1 - F)^2 (1 + F^2 + F^4 + ...) = (1 - F)^2 / (1 - F^2) = (1 - F) / (1 + F), F = ((n-1)/(n+1))^2,
// from the inter-reflections inside the pane (the world is black, so the front reflection adds
// nothing and the pane's own reflection of the emitter goes back to it).
TEST(GlassRender, SmoothSlabTransmitsTheClosedForm) {
  for (float ior : {2.4f, 3.5f}) {  // where the inter-reflections matter: 3.0 % and 7.4 % of (1 - F)^2
    Scene scene;
    const uint32_t pane = scene.add_material(glass(0.0f, ior));
    Material emitter;
    emitter.base_color = Vec3(0.0f);
    emitter.specular = 0.0f;
    emitter.emission = Vec3(2.0f);
    const uint32_t light = scene.add_material(emitter);
    const float h = 200.0f;
    // The pane: top face (normal +z) at z = 0.1, bottom face (normal -z) at z = 0.
    add_quad(scene, Vec3(-h, -h, 0.1f), Vec3(h, -h, 0.1f), Vec3(h, h, 0.1f), Vec3(-h, h, 0.1f), pane);
    add_quad(scene, Vec3(-h, -h, 0.0f), Vec3(-h, h, 0.0f), Vec3(h, h, 0.0f), Vec3(h, -h, 0.0f), pane);
    add_quad(scene, Vec3(-h, -h, -1.0f), Vec3(h, -h, -1.0f), Vec3(h, h, -1.0f), Vec3(-h, h, -1.0f), light);
    look_down(scene, 5.0f, 2000.0f);  // +-0.045 m: normal incidence within 0.5 degrees
    const RenderResult r = render(scene, settings(16, 256, 32));
    const float F = sqr((ior - 1.0f) / (ior + 1.0f));
    const float expected = 2.0f * (1.0f - F) / (1.0f + F);
    const float mean = mean_rgb(r.image).r;
    std::printf("slab ior %.1f: %.5f, closed form %.5f (single pass (1-F)^2: %.5f)\n", ior, mean, expected,
                2.0f * sqr(1.0f - F));
    // Each sample is 0 or 2 (delta lobes chosen in proportion to F and 1 - F): relative standard
    // error sqrt((1 - t) / t / 65536) = 0.25 % at t = 0.71 transmitted; 1 % is 4 of them.
    EXPECT_NEAR(mean, expected, 0.01f * expected) << "ior " << ior;
    EXPECT_EQ(r.nonfinite_samples, 0u);
  }
}

// A single rough glass sheet (one face, nothing behind it) over a point light: a delta light
// can only be reached by NEE, here on the sheet's far side (two-sided light choice, the shadow
// ray leaving below the sheet). Seen straight down through a narrow camera, the pixel is the
// glass's eval times the light's irradiance I / d^2 (Cycles' point light: I = P / (4 pi)).
// The generic path gives the same image as the specialised one.
TEST(GlassRender, DeltaLightSeenThroughRoughGlassByNee) {
  for (bool inside : {false, true}) {
    Scene scene;
    const Material m = glass(0.8f);
    const uint32_t sheet = scene.add_material(m);
    const float h = 50.0f;
    if (inside)  // normal -z: the camera looks at the sheet's back, from inside the glass
      add_quad(scene, Vec3(-h, -h, 0.0f), Vec3(-h, h, 0.0f), Vec3(h, h, 0.0f), Vec3(h, -h, 0.0f), sheet);
    else add_quad(scene, Vec3(-h, -h, 0.0f), Vec3(h, -h, 0.0f), Vec3(h, h, 0.0f), Vec3(-h, h, 0.0f), sheet);
    const float power = 50.0f, d = 1.0f;
    scene.lights().add_point(Vec3(0.0f, 0.0f, -d), power, Vec3(1.0f), 0.0f);
    look_down(scene, 5.0f, 10000.0f);
    RenderSettings s = settings(8, 16, 4);
    const RenderResult a = render(scene, s);
    s.specialize = false;
    const RenderResult b = render(scene, s);
    EXPECT_EQ(a.nonfinite_samples, 0u);
    const MaterialBsdf bsdf(m, BrdfModel::Principled);
    const Vec3 f = bsdf.eval(Vec3(0, 0, 1), Vec3(0, 0, -1), inside);
    const float expected = f.g * power / (4.0f * kPi * d * d);
    const float mean = mean_rgb(a.image).g;
    std::printf("delta light through rough glass (%s): %.5f, expected %.5f\n", inside ? "inside" : "outside", mean,
                expected);
    EXPECT_GT(expected, 0.1f);
    EXPECT_NEAR(mean, expected, 0.01f * expected);
    EXPECT_NEAR(mean_rgb(b.image).g, mean, 1e-6f * mean);  // same samples, same paths
  }
}

}  // namespace
}  // namespace torrance
