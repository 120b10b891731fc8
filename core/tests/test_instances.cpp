// Instancing: a prototype placed by instance transforms must trace, shade and light exactly like
// the world-space copies the flattening export used to make (positions by M, normals by M^-T,
// corners 1 and 2 swapped when M mirrors), so both are compared hit by hit and pixel by pixel.
#include "torrance/integrator/integrator.h"
#include "torrance/util/sampling.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace torrance {
namespace {

using Matrix = std::array<float, 12>;  // row-major 3x4
constexpr float kInfinity = 1e30f;

// A small tent: 4 triangles around a ridge, tilted corner normals, UVs, two material slots.
struct Proto {
  std::vector<float> positions{-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, 0, 0, 0.8f};
  std::vector<int64_t> triangles{0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
  std::vector<int64_t> slots{0, 1, 0, 1};
  std::vector<float> normals, uvs;
  Proto() {
    const float* p = positions.data();
    for (size_t i = 0; i < triangles.size(); ++i) {
      const int64_t v = triangles[i];
      // smooth-ish normals: radial tilt plus z, unnormalised on purpose
      normals.insert(normals.end(), {0.6f * p[3 * v], 0.6f * p[3 * v + 1], 1.0f + 0.2f * float(i % 3)});
      uvs.insert(uvs.end(), {0.5f + 0.45f * p[3 * v] + 0.1f * p[3 * v + 2], 0.5f + 0.3f * p[3 * v + 1]});
    }
  }
  size_t num_vertices() const { return positions.size() / 3; }
  size_t num_triangles() const { return triangles.size() / 3; }
  // Only positions and triangles: flat normals, material slot 0, no UVs.
  void add_plain_to(Scene& scene) const {
    scene.add_prototype(positions.data(), num_vertices(), triangles.data(), num_triangles(), nullptr, nullptr);
  }
};

// Straight down onto the prototype at the origin, next to its ridge.
Ray ray_down() {
  Ray down;
  down.origin = Vec3(0.1f, 0.05f, 5);
  down.dir = Vec3(0, 0, -1);
  down.tmin = 0.0f;
  down.tmax = kInfinity;
  return down;
}

// The flattening export, written independently of the core: a world-space copy of the prototype.
void add_flattened(Scene& scene, const Proto& proto, const Matrix& m, const std::vector<int64_t>& table) {
  const glm::dmat3 lin(m[0], m[4], m[8], m[1], m[5], m[9], m[2], m[6], m[10]);  // columns
  const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(lin));
  const bool flip = glm::determinant(lin) < 0.0;
  std::vector<float> pos;
  for (size_t v = 0; v < proto.num_vertices(); ++v) {
    const glm::dvec3 p(proto.positions[3 * v], proto.positions[3 * v + 1], proto.positions[3 * v + 2]);
    const glm::dvec3 w = lin * p + glm::dvec3(m[3], m[7], m[11]);
    pos.insert(pos.end(), {float(w.x), float(w.y), float(w.z)});
  }
  std::vector<int64_t> tris = proto.triangles, mats;
  std::vector<float> normals(proto.normals.size()), uvs = proto.uvs;
  for (size_t c = 0; c < proto.normals.size() / 3; ++c) {
    const glm::dvec3 n = normal_matrix * glm::dvec3(glm::normalize(
                                             Vec3(proto.normals[3 * c], proto.normals[3 * c + 1], proto.normals[3 * c + 2])));
    const Vec3 nf = glm::normalize(Vec3(n));
    normals[3 * c] = nf.x, normals[3 * c + 1] = nf.y, normals[3 * c + 2] = nf.z;
  }
  for (size_t t = 0; t < proto.num_triangles(); ++t) {
    mats.push_back(table[std::min<size_t>(proto.slots[t], table.size() - 1)]);
    if (!flip) continue;
    std::swap(tris[3 * t + 1], tris[3 * t + 2]);
    for (int k = 0; k < 3; ++k) std::swap(normals[9 * t + 3 + k], normals[9 * t + 6 + k]);
    for (int k = 0; k < 2; ++k) std::swap(uvs[6 * t + 2 + k], uvs[6 * t + 4 + k]);
  }
  scene.add_mesh(pos.data(), proto.num_vertices(), tris.data(), proto.num_triangles(), normals.data(), mats.data(),
                 uvs.data());
}

Matrix affine(const glm::mat3& lin, const Vec3& t) {
  return {lin[0][0], lin[1][0], lin[2][0], t.x, lin[0][1], lin[1][1], lin[2][1], t.y, lin[0][2], lin[1][2], lin[2][2], t.z};
}

glm::mat3 rotation_z(float a) { return glm::mat3(std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0, 0, 0, 1); }
glm::mat3 rotation_x(float a) { return glm::mat3(1, 0, 0, 0, std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a)); }
glm::mat3 scale(float x, float y, float z) { return glm::mat3(x, 0, 0, 0, y, 0, 0, 0, z); }

// Translation, rotation, non-uniform scale, mirroring (one and three negative axes), shear.
std::vector<Matrix> test_transforms() {
  return {affine(glm::mat3(1.0f), Vec3(-3, -3, 0)),
          affine(rotation_z(0.7f) * rotation_x(0.3f), Vec3(0, -3, 0.2f)),
          affine(scale(2.5f, 0.4f, 1.7f), Vec3(3, -3, 0)),
          affine(rotation_z(-0.4f) * scale(-1.0f, 1.3f, 0.6f), Vec3(-3, 0, 0.1f)),
          affine(scale(-0.8f, -1.2f, -0.9f), Vec3(0, 0, 1.0f)),  // all three negative: det < 0, upside down
          affine(glm::mat3(1, 0, 0, 0.6f, 1, 0, 0, 0.3f, 1.4f) * rotation_z(1.1f), Vec3(3, 0, 0)),
          affine(rotation_x(2.6f) * scale(0.7f, -0.5f, 1.9f), Vec3(0, 3, 0.8f))};
}

struct Scenes {
  Scene instanced, flattened;
};

// Two materials (slot 0, 1) and an emissive one used by the last instance's table.
void build(Scenes& s, bool textured) {
  for (Scene* scene : {&s.instanced, &s.flattened}) {
    MaterialTextures tex;
    if (textured) {
      std::vector<float> pixels;
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
          pixels.insert(pixels.end(), {0.5f + 0.4f * float((x + y) % 2), 0.5f + 0.05f * x, 0.9f - 0.05f * y});
      scene->add_texture(Texture(8, 8, 3, pixels.data(), ColorSpace::Linear, Interpolation::Linear));
      tex.base_color = 0;
      tex.normal = 0;  // the checker read as a normal map: strongly tilted normals
    }
    Material a, b, e;
    a.base_color = Vec3(0.8f, 0.5f, 0.3f);
    a.roughness = 0.3f;
    b.base_color = Vec3(0.2f, 0.6f, 0.9f);
    b.metallic = 1.0f;
    b.roughness = 0.2f;
    e.base_color = Vec3(0.1f);
    e.emission = Vec3(4.0f, 3.0f, 2.0f);
    scene->add_material(a, tex);
    scene->add_material(b);
    scene->add_material(e);
    Material ground;
    scene->add_material(ground);
    const float quad[] = {-20, -20, -0.5f, 20, -20, -0.5f, 20, 20, -0.5f, -20, 20, -0.5f};
    const int64_t quad_tris[] = {0, 1, 2, 0, 2, 3}, quad_mats[] = {3, 3};
    scene->add_mesh(quad, 4, quad_tris, 2, nullptr, quad_mats);
    CameraParams cam;
    cam.camera_to_world = {1, 0, 0, 0, 0, 0.8f, -0.6f, -9, 0, 0.6f, 0.8f, 8, 0, 0, 0, 1};
    cam.lens_mm = 30.0f;
    scene->set_camera(cam);
    scene->lights().add_point(Vec3(2, -4, 6), 800.0f, Vec3(1.0f), 0.3f);
  }
  const Proto proto;
  const std::vector<Matrix> xf = test_transforms();
  const std::vector<int64_t> table{0, 1}, emissive_table{2, 1};
  s.instanced.add_prototype(proto.positions.data(), proto.num_vertices(), proto.triangles.data(),
                            proto.num_triangles(), proto.normals.data(), proto.slots.data(), proto.uvs.data());
  std::vector<int64_t> tables;
  for (size_t i = 0; i < xf.size(); ++i) {
    const auto& t = i + 1 == xf.size() || i == 3 ? emissive_table : table;
    tables.insert(tables.end(), t.begin(), t.end());
    add_flattened(s.flattened, proto, xf[i], t);
  }
  s.instanced.add_instances(0, &xf[0][0], xf.size(), tables.data(), 2, true);
  s.instanced.commit();
  s.flattened.commit();
}

void expect_near(const Vec3& a, const Vec3& b, float tol, const char* what, int ray) {
  EXPECT_LT(glm::length(a - b), tol) << what << " differs on ray " << ray << ": (" << a.x << ", " << a.y << ", "
                                     << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")";
}

TEST(Instances, SurfaceHitsMatchWorldSpaceCopies) {
  Scenes s;
  build(s, true);
  EXPECT_EQ(s.instanced.num_triangles(), s.flattened.num_triangles());
  EXPECT_EQ(s.instanced.lights().num_emissive_triangles(), s.flattened.lights().num_emissive_triangles());
  EXPECT_EQ(s.instanced.num_material_tables(), 2u);
  Rng rng(7, 0, 0);
  int hits = 0, mirrored_hits = 0;
  for (int i = 0; i < 4000; ++i) {
    Ray ray;
    // From above and below, toward points spread over the instances.
    const Vec3 target(-4.5f + 9 * rng.next_1d(), -4.5f + 9 * rng.next_1d(), -0.4f + 2 * rng.next_1d());
    ray.origin = Vec3(-6 + 12 * rng.next_1d(), -6 + 12 * rng.next_1d(), i % 4 == 0 ? -0.45f : 6.0f);
    ray.dir = glm::normalize(target - ray.origin);
    ray.tmin = 0.0f;
    ray.tmax = kInfinity;
    SurfaceHit a, b;
    const bool ha = s.instanced.intersect(ray, a), hb = s.flattened.intersect(ray, b);
    ASSERT_EQ(ha, hb) << "ray " << i;
    if (!ha) continue;
    if (std::abs(a.t - b.t) > 1e-4f * b.t) continue;  // a different triangle at an edge (float noise)
    ++hits;
    mirrored_hits += a.position.x < -2 && a.position.y > -1.5f;
    EXPECT_NEAR(a.t, b.t, 1e-4f * b.t);
    expect_near(a.position, b.position, 1e-4f, "position", i);
    expect_near(a.geometric_normal, b.geometric_normal, 1e-4f, "geometric normal", i);
    expect_near(a.shading_normal, b.shading_normal, 1e-4f, "shading normal", i);
    EXPECT_EQ(a.material, b.material) << "ray " << i;
    EXPECT_EQ(a.emitter, b.emitter) << "ray " << i;
    EXPECT_LT(glm::length(a.uv - b.uv), 1e-4f) << "ray " << i;
    expect_near(a.tangent, b.tangent, 1e-3f, "tangent", i);
    EXPECT_NEAR(a.uv_per_metre, b.uv_per_metre, 1e-4f * b.uv_per_metre) << "ray " << i;
    EXPECT_EQ(a.bitangent_sign, b.bitangent_sign) << "ray " << i;
    // The normal-mapped normal, which depends on all of the above.
    expect_near(s.instanced.normal_mapped(a.material, a, a.shading_normal),
                s.flattened.normal_mapped(b.material, b, b.shading_normal), 1e-3f, "normal-mapped normal", i);
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(mirrored_hits, 20);
}

struct Diff {
  float max_pixel = 0, mean = 0, max_block = 0;
};

Diff compare(const Image& a, const Image& b) {
  Diff d;
  double sum_a = 0, sum_b = 0;
  for (size_t i = 0; i < a.rgba.size(); ++i) {
    d.max_pixel = std::max(d.max_pixel, std::abs(a.rgba[i] - b.rgba[i]));
    sum_a += a.rgba[i];
    sum_b += b.rgba[i];
  }
  d.mean = float(std::abs(sum_a - sum_b) / a.rgba.size());
  for (int by = 0; by < a.height; by += 8)
    for (int bx = 0; bx < a.width; bx += 8)
      for (int c = 0; c < 3; ++c) {
        double ba = 0, bb = 0;
        for (int y = by; y < by + 8; ++y)
          for (int x = bx; x < bx + 8; ++x) {
            ba += a.rgba[4 * (y * a.width + x) + c];
            bb += b.rgba[4 * (y * a.width + x) + c];
          }
        d.max_block = std::max(d.max_block, float(std::abs(ba - bb) / 64));
      }
  return d;
}

TEST(Instances, RendersMatchWorldSpaceCopies) {
  for (bool textured : {false, true}) {
    Scenes s;
    build(s, textured);
    RenderSettings settings;
    settings.width = 48;
    settings.height = 32;
    settings.samples = 16;
    const Image a = render(s.instanced, settings).image;
    const Image b = render(s.flattened, settings).image;
    const Diff d = compare(a, b);
    double mean = 0;
    for (float x : b.rgba) mean += x;
    mean /= b.rgba.size();
    // The same geometry with the same seed: equal up to float noise in hit points, which can
    // send a rare path elsewhere; means must agree far better than Monte Carlo noise.
    std::printf("[ instanced vs flattened%s ] image mean %.4f, max pixel diff %.3g, mean diff %.3g, max 8x8 block "
                "diff %.3g\n",
                textured ? ", textured" : "", mean, d.max_pixel, d.mean, d.max_block);
    EXPECT_LT(d.mean, 1e-5 * mean) << "textured " << textured;
    EXPECT_LT(d.max_block, 1e-4 * mean) << "textured " << textured;
  }
}

TEST(Instances, MovingAndRemovingUpdatesHitsAndLights) {
  Scene scene;
  Material e;
  e.emission = Vec3(2.0f);
  scene.add_material(Material{});
  scene.add_material(e);
  const Proto proto;
  proto.add_plain_to(scene);
  const Matrix at_origin = affine(glm::mat3(1.0f), Vec3(0.0f)), moved = affine(scale(2, 2, 2), Vec3(5, 0, 0));
  const int64_t table[] = {1};
  const int64_t first = scene.add_instances(0, at_origin.data(), 1, table, 1);
  const Matrix two[] = {affine(glm::mat3(1.0f), Vec3(0, 5, 0)), affine(glm::mat3(1.0f), Vec3(0, -5, 0))};
  scene.add_instances(0, two[0].data(), 2, table, 1);
  scene.commit();
  EXPECT_EQ(scene.lights().num_emissive_triangles(), 12u);
  const Ray down = ray_down();
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(down, hit));
  EXPECT_NEAR(hit.position.z, 0.8f * (1 - 0.1f), 1e-4f);
  EXPECT_GE(hit.emitter, 0);
  scene.set_instance_transforms(&first, moved.data(), 1);
  scene.commit();
  EXPECT_FALSE(scene.intersect(down, hit));
  Ray moved_down = down;
  moved_down.origin.x += 5;
  ASSERT_TRUE(scene.intersect(moved_down, hit));
  EXPECT_NEAR(hit.position.z, 1.6f * (1 - 0.05f), 1e-4f);  // scaled by 2
  ASSERT_GE(hit.emitter, 0);
  // The light must hold the moved triangles: the same MIS density as a scene built moved.
  Scene fresh;
  fresh.add_material(Material{});
  fresh.add_material(e);
  proto.add_plain_to(fresh);
  fresh.add_instances(0, moved.data(), 1, table, 1);
  fresh.add_instances(0, two[0].data(), 2, table, 1);
  fresh.commit();
  SurfaceHit fresh_hit;
  ASSERT_TRUE(fresh.intersect(moved_down, fresh_hit));
  EXPECT_EQ(hit.emitter, fresh_hit.emitter);
  const Vec3 p(4, 1, 3);
  const float pdf = fresh.lights().mesh_light_pdf(size_t(hit.emitter), p, Vec3(0, 0, -1), hit.position);
  EXPECT_GT(pdf, 0.0f);
  EXPECT_NEAR(scene.lights().mesh_light_pdf(size_t(hit.emitter), p, Vec3(0, 0, -1), hit.position), pdf, 1e-5f * pdf);
  const int64_t ids[] = {first, first + 1};
  scene.remove_instances(ids, 2);
  scene.commit();
  EXPECT_FALSE(scene.intersect(moved_down, hit));
  EXPECT_EQ(scene.num_instances(), 1u);
  EXPECT_EQ(scene.lights().num_emissive_triangles(), 4u);
  EXPECT_THROW(scene.remove_instances(ids, 1), std::invalid_argument);  // already removed
  EXPECT_THROW(scene.set_instance_transforms(ids, moved.data(), 1), std::invalid_argument);
}

TEST(Instances, BadInputsAndZeroScale) {
  Scene scene;
  scene.add_material(Material{});
  const Proto proto;
  const int64_t bad_slots[] = {0, -1, 0, 0};
  EXPECT_THROW(scene.add_prototype(proto.positions.data(), proto.num_vertices(), proto.triangles.data(),
                                   proto.num_triangles(), nullptr, bad_slots),
               std::invalid_argument);
  proto.add_plain_to(scene);
  Matrix m = affine(glm::mat3(1.0f), Vec3(0.0f));
  const int64_t table[] = {0}, bad_table[] = {1};
  EXPECT_THROW(scene.add_instances(1, m.data(), 1, table, 1), std::invalid_argument);
  EXPECT_THROW(scene.add_instances(0, m.data(), 1, bad_table, 1), std::invalid_argument);
  EXPECT_THROW(scene.add_instances(0, m.data(), 1, table, 0), std::invalid_argument);
  m[5] = std::nanf("");
  EXPECT_THROW(scene.add_instances(0, m.data(), 1, table, 1), std::invalid_argument);
  EXPECT_EQ(scene.num_instances(), 0u);
  // Zero scale hides the instance (no hit, no triangles) until a regular matrix comes.
  m = affine(scale(1, 1, 0), Vec3(0.0f));
  const int64_t id = scene.add_instances(0, m.data(), 1, table, 1);
  scene.commit();
  EXPECT_EQ(scene.num_hidden_instances(), 1u);
  EXPECT_EQ(scene.num_triangles(), 0u);
  const Ray down = ray_down();
  SurfaceHit hit;
  EXPECT_FALSE(scene.intersect(down, hit));
  m = affine(glm::mat3(1.0f), Vec3(0.0f));
  scene.set_instance_transforms(&id, m.data(), 1);
  scene.commit();
  EXPECT_EQ(scene.num_hidden_instances(), 0u);
  EXPECT_TRUE(scene.intersect(down, hit));
}

}  // namespace
}  // namespace torrance
