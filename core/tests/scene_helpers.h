// Small scenes for the core's render tests (test_glass_render.cpp, test_alpha.cpp).
#pragma once

#include "torrance/integrator.h"

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

}  // namespace torrance::test
