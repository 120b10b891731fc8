// Small scenes for the core's render tests (test_glass_render.cpp, test_alpha.cpp).
#pragma once

#include "torrance/integrator/integrator.h"
#include "torrance/bsdfs/material_bsdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

namespace torrance::test {

// A quad (two triangles) with corners a, b, c, d counter-clockwise seen from its normal's side.
inline void add_quad(Scene& scene, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int64_t material) {
  const float p[] = {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z};
  const int64_t tris[] = {0, 1, 2, 0, 2, 3}, mats[] = {material, material};
  scene.add_mesh(p, 4, tris, 2, nullptr, mats);
}

// The same quad with UVs (0, 0), (1, 0), (1, 1), (0, 1) at a, b, c, d.
inline void add_quad_uv(Scene& scene, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int64_t material) {
  const float p[] = {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, d.x, d.y, d.z};
  const int64_t tris[] = {0, 1, 2, 0, 2, 3}, mats[] = {material, material};
  const float uvs[] = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
  scene.add_mesh(p, 4, tris, 2, nullptr, mats, uvs);
}

// A box (12 flat triangles, wound outwards) of half-extents `half` about `center`.
inline void add_box(Scene& scene, const Vec3& center, const Vec3& half, int64_t material) {
  const Vec3 lo = center - half, hi = center + half;
  auto corner = [&](int i) { return Vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
  // Each face's corners counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) add_quad(scene, corner(f[0]), corner(f[1]), corner(f[2]), corner(f[3]), material);
}

// A wavy sheet over x0..x1 by y0..y1 (n x n cells): z = amplitude sin(k x) cos(k y), k = 2, with
// its true normals at the corners (smooth shading).
inline void add_wavy_sheet(Scene& scene, float x0, float x1, float y0, float y1, int n, float amplitude, int64_t material) {
  const float k = 2.0f;
  std::vector<float> positions, normals;
  std::vector<int64_t> triangles, materials;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = x0 + (x1 - x0) * float(i) / float(n), y = y0 + (y1 - y0) * float(j) / float(n);
      const Vec3 normal = glm::normalize(Vec3(-amplitude * k * std::cos(k * x) * std::cos(k * y),
                                              amplitude * k * std::sin(k * x) * std::sin(k * y), 1.0f));
      positions.insert(positions.end(), {x, y, amplitude * std::sin(k * x) * std::cos(k * y)});
      normals.insert(normals.end(), {normal.x, normal.y, normal.z});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int64_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      triangles.insert(triangles.end(), {a, b, c, a, c, d});
      materials.insert(materials.end(), {material, material});
    }
  // Per-corner normals: the scene takes three per triangle.
  std::vector<float> corner_normals;
  for (int64_t v : triangles) corner_normals.insert(corner_normals.end(), normals.begin() + 3 * v, normals.begin() + 3 * v + 3);
  scene.add_mesh(positions.data(), positions.size() / 3, triangles.data(), triangles.size() / 3,
                 corner_normals.data(), materials.data());
}

// A size x size render of `samples` per pixel, `bounces` bounces, shaded by `model`.
inline RenderSettings square_render(int size, int samples, int bounces, BrdfModel model) {
  RenderSettings s;
  s.width = s.height = size;
  s.samples = samples;
  s.max_bounces = bounces;
  s.brdf_model = model;
  return s;
}

// A narrow camera at (0, 0, height) looking straight down (-z); lens 2000 mm sees +-0.045 h/5.
inline void look_down(Scene& scene, float height, float lens_mm) {
  CameraParams cam;
  cam.camera_to_world = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, height, 0, 0, 0, 1};
  cam.lens_mm = lens_mm;
  cam.clip_end = 1000.0f;
  scene.set_camera(cam);
}

// Mean RGB of an RGBA image.
inline Vec3 mean_rgb(const Image& img) {
  Vec3 sum(0.0f);
  for (size_t i = 0; i < img.rgba.size(); i += 4) sum += Vec3(img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]);
  return sum / float(img.rgba.size() / 4);
}

// A rough white-to-grey diffuse material: Lambert-like, no specular layer.
inline Material diffuse_material(const Vec3& color) {
  Material m;
  m.base_color = color;
  m.specular = 0.0f;
  m.roughness = 1.0f;
  return m;
}

// The render's BSDFs of a scene's materials (Principled), as MirrorImages takes them.
inline std::vector<MaterialBsdf> principled_bsdfs(const Scene& scene) {
  std::vector<MaterialBsdf> bsdfs;
  for (uint32_t i = 0; i < scene.num_materials(); ++i) bsdfs.emplace_back(scene.material(i), BrdfModel::Principled);
  return bsdfs;
}

// A camera inside the closed room (add_closed_room), half a metre above its centre, looking down.
inline void look_down_in_room(Scene& scene) {
  CameraParams cam;
  cam.camera_to_world = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0.5f, 0, 0, 0, 1};
  cam.lens_mm = 25.0f;
  scene.set_camera(cam);
}

// A floor of thin stripes, white and black, several to a pixel (0.04 m wide, seen from 3 m with an
// 18 mm lens), under a high sun and a dim sky: the image's variance is which stripe a sample
// sees, and its light is almost all direct.
inline void add_sunlit_stripes(Scene& scene) {
  const int64_t white = scene.add_material(diffuse_material(Vec3(0.9f)));
  const int64_t black = scene.add_material(diffuse_material(Vec3(0.02f)));
  constexpr float kWidth = 0.04f;
  for (int i = 0; i < 150; ++i) {
    const float x0 = -3.0f + i * kWidth, x1 = x0 + kWidth;
    add_quad(scene, {x0, -4, 0}, {x1, -4, 0}, {x1, 4, 0}, {x0, 4, 0}, i % 2 ? black : white);
  }
  scene.lights().add_sun(glm::normalize(Vec3(0.3f, 0.5f, -1.0f)), 3.0f, Vec3(1.0f), 0.01f);
  scene.lights().set_world(Vec3(1.0f), 0.05f);
  look_down(scene, 3.0f, 18.0f);
}

// The walls, floor and ceiling of a closed 2 m cube about the origin, facing inwards (the
// ceiling of `ceiling` if given).
inline void add_closed_room(Scene& scene, int64_t material, int64_t ceiling = -1) {
  const Vec3 c[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  add_quad(scene, c[0], c[1], c[2], c[3], material);  // floor
  add_quad(scene, c[4], c[7], c[6], c[5], ceiling >= 0 ? ceiling : material);  // ceiling
  add_quad(scene, c[0], c[4], c[5], c[1], material);
  add_quad(scene, c[1], c[5], c[6], c[2], material);
  add_quad(scene, c[2], c[6], c[7], c[3], material);
  add_quad(scene, c[3], c[7], c[4], c[0], material);
}

// Mean of the green channel over 4 x 4 blocks of the size x size pixels from (x0, y0) (size a
// multiple of 4).
inline std::vector<double> block_means(const Image& img, int x0, int y0, int size) {
  std::vector<double> blocks(16, 0.0);
  const int block = size / 4;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      blocks[(y / block) * 4 + x / block] += img.rgba[(size_t(y + y0) * img.width + x + x0) * 4 + 1];
  for (double& b : blocks) b /= double(block * block);
  return blocks;
}

// The same over a whole 32 x 32 image (blocks of 8 x 8 pixels).
inline std::vector<double> block_means_32(const Image& img) { return block_means(img, 0, 0, 32); }

// Mean over the pixels of the green channel's variance over the seeds' images.
inline double mean_pixel_variance(const std::vector<Image>& images) {
  const size_t n = images.size(), pixels = images[0].rgba.size() / 4;
  double total = 0.0;
  for (size_t p = 0; p < pixels; ++p) {
    double mean = 0.0, square = 0.0;
    for (const Image& img : images) mean += img.rgba[4 * p + 1] / n;
    for (const Image& img : images) square += (img.rgba[4 * p + 1] - mean) * (img.rgba[4 * p + 1] - mean);
    total += square / (n - 1);
  }
  return total / pixels;
}

// Two renderers' block means (block_means_32) over the same seeds, compared: the ratio of their
// image means (b over a), and |mean difference| / its standard error (from both sets' spread over
// the seeds) for the whole image and for the worst block.
struct SeedAgreement {
  double ratio = 1.0, image_z = 0.0, worst_block_z = 0.0;
};
inline SeedAgreement compare_over_seeds(const std::vector<std::vector<double>>& a,
                                        const std::vector<std::vector<double>>& b) {
  const size_t seeds = a.size();
  auto z_score = [&](auto value) {
    double ma = 0, mb = 0, va = 0, vb = 0;
    for (size_t s = 0; s < seeds; ++s) {
      ma += value(a[s]) / seeds;
      mb += value(b[s]) / seeds;
    }
    for (size_t s = 0; s < seeds; ++s) {
      va += (value(a[s]) - ma) * (value(a[s]) - ma) / (seeds - 1);
      vb += (value(b[s]) - mb) * (value(b[s]) - mb) / (seeds - 1);
    }
    return std::pair<double, double>(mb / ma, std::abs(mb - ma) / std::sqrt((va + vb) / seeds + 1e-12));
  };
  SeedAgreement out;
  for (size_t block = 0; block < a[0].size(); ++block)
    out.worst_block_z = std::max(
        out.worst_block_z, z_score([block](const std::vector<double>& blocks) { return blocks[block]; }).second);
  std::tie(out.ratio, out.image_z) = z_score([](const std::vector<double>& blocks) {
    double sum = 0.0;
    for (double v : blocks) sum += v;
    return sum;
  });
  return out;
}

// Two renderers agree: image means within ratio_tolerance of each other, and the whole image's
// and the worst block's differences within 4 and 4.5 standard errors (16 blocks: |z| > 4.5 by
// chance has odds ~1e-4).
inline void expect_agreement(const SeedAgreement& a, double ratio_tolerance = 0.01) {
  EXPECT_NEAR(a.ratio, 1.0, ratio_tolerance);
  EXPECT_LT(a.image_z, 4.0);
  EXPECT_LT(a.worst_block_z, 4.5);
}

}  // namespace torrance::test
