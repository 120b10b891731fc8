// Cameras: Blender's orthographic projection, the thin-lens depth of field (focus plane sharp,
// circle of confusion of the thin-lens formula, anamorphic ratio), uniform aperture sampling,
// and pinhole rays that do not change when depth of field is off.
#include "torrance/camera/camera.h"
#include "torrance/util/limits.h"

#include "torrance/util/sampling.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

namespace torrance {
namespace {

// A camera at (1, 2, 3), turned 30 degrees about Z and tilted 20 degrees down: row-major
// camera-to-world like Blender's matrix_world.
CameraParams turned_camera() {
  const float a = 0.5235988f, b = 0.3490659f;
  const glm::mat3 rz(std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0, 0, 0, 1);  // columns
  const glm::mat3 rx(1, 0, 0, 0, std::cos(b), std::sin(b), 0, -std::sin(b), std::cos(b));
  const glm::mat3 r = rz * rx;
  CameraParams p;
  const Vec3 t(1, 2, 3);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) p.camera_to_world[4 * i + j] = r[j][i];
    p.camera_to_world[4 * i + 3] = t[i];
  }
  return p;
}

struct Frame3 {
  Vec3 origin, x, y, z;  // z = the camera's local +Z (it looks down -z)
};
Frame3 frame_of(const CameraParams& p) {
  const auto& m = p.camera_to_world;
  return {Vec3(m[3], m[7], m[11]), Vec3(m[0], m[4], m[8]), Vec3(m[1], m[5], m[9]), Vec3(m[2], m[6], m[10])};
}

float distance_to_line(const Vec3& p, const Ray& r) {
  const Vec3 v = p - r.origin;
  return glm::length(v - glm::dot(v, r.dir) * r.dir);
}

// Blender's orthographic projection written out: the sensor-fit dimension spans ortho_scale,
// shifts move the view by shift * ortho_scale, raster y counted from the bottom.
Vec2 blender_ortho_pixel(const CameraParams& p, int w, int h, float aspect_x, float aspect_y, const Vec3& world) {
  const Frame3 f = frame_of(p);
  const Vec3 v = world - f.origin;
  const float xc = glm::dot(v, f.x), yc = glm::dot(v, f.y);
  const float xr = w * aspect_x, yr = h * aspect_y;
  bool horizontal = xr > yr;
  if (p.sensor_fit == SensorFit::Horizontal) horizontal = true;
  if (p.sensor_fit == SensorFit::Vertical) horizontal = false;
  const float s = p.ortho_scale;
  const float width_units = horizontal ? s : s * xr / yr, height_units = horizontal ? s * yr / xr : s;
  const float px = w * ((xc - s * p.shift_x) / width_units + 0.5f);
  const float py_bottom = h * ((yc - s * p.shift_y) / height_units + 0.5f);
  return Vec2(px, py_bottom);
}

TEST(Camera, OrthographicRaysAreParallelAndProjectLikeBlender) {
  struct Case {
    int w, h;
    float ax, ay;
    SensorFit fit;
    float shift_x, shift_y;
  };
  const Case cases[] = {{200, 100, 1, 1, SensorFit::Auto, 0, 0},        {100, 200, 1, 1, SensorFit::Auto, 0, 0},
                        {200, 100, 1, 1, SensorFit::Vertical, 0, 0},    {100, 200, 1, 1, SensorFit::Horizontal, 0, 0},
                        {200, 100, 1, 1, SensorFit::Auto, 0.2f, -0.1f}, {160, 100, 2, 1, SensorFit::Auto, 0, 0.3f},
                        {120, 100, 1, 2, SensorFit::Auto, 0, 0}};
  const Vec3 points[] = {Vec3(0.5f, 5.0f, 0.5f), Vec3(2.3f, 7.0f, -1.0f), Vec3(-0.7f, 4.0f, 1.4f)};
  for (const Case& c : cases) {
    CameraParams p = turned_camera();
    p.type = CameraType::Orthographic;
    p.ortho_scale = 4.5f;
    p.sensor_fit = c.fit;
    p.shift_x = c.shift_x;
    p.shift_y = c.shift_y;
    p.clip_start = 0.5f;
    const Camera cam(p, c.w, c.h, c.ax, c.ay);
    const Frame3 f = frame_of(p);
    for (const Vec3& world : points) {
      const Vec2 px = blender_ortho_pixel(p, c.w, c.h, c.ax, c.ay, world);
      const Ray r = cam.generate_ray(px.x, float(c.h) - px.y, Vec2(0.3f, 0.8f));
      EXPECT_LT(distance_to_line(world, r), 1e-4f) << c.w << "x" << c.h << " fit " << int(c.fit);
      EXPECT_LT(glm::length(r.dir + f.z), 1e-6f);  // parallel to the view axis
      // Clipping along the view axis: the segment starts on the clip_start plane.
      EXPECT_NEAR(glm::dot(r.origin + r.tmin * r.dir - f.origin, -f.z), 0.5f, 1e-5f);
      EXPECT_NEAR(glm::dot(r.origin + r.tmax * r.dir - f.origin, -f.z), 100.0f, 1e-3f);
    }
    // All rays parallel, origins spread over the view plane (ortho_scale across the fitted side).
    const Ray left = cam.generate_ray(0.0f, 0.5f * c.h), right = cam.generate_ray(float(c.w), 0.5f * c.h);
    EXPECT_EQ(left.dir, right.dir);
    const float xr = c.w * c.ax, yr = c.h * c.ay;
    const bool horizontal = c.fit == SensorFit::Horizontal || (c.fit == SensorFit::Auto && xr > yr);
    EXPECT_NEAR(glm::length(right.origin - left.origin), horizontal ? 4.5f : 4.5f * xr / yr, 1e-4f);
    EXPECT_EQ(cam.pixel_spread(), 0.0f);
  }
}

// The pinhole ray before depth of field existed (the formula of the previous camera.cpp).
Ray previous_pinhole(const CameraParams& p, int w, int h, float x, float y_from_top) {
  const Frame3 f = frame_of(p);
  // The axes as main's pinhole camera normalised them before depth of field (robust_normalize).
  const Vec3 right = robust_normalize(f.x), up = robust_normalize(f.y), fwd = -robust_normalize(f.z);
  const float hh = p.sensor_width_mm / (2.0f * p.lens_mm);
  const float half_w = hh, half_h = hh * float(h) / float(w);
  const float cx = half_w * (2.0f * x / float(w) - 1.0f) + 2.0f * hh * p.shift_x;
  const float cy = half_h * (2.0f * (float(h) - y_from_top) / float(h) - 1.0f) + 2.0f * hh * p.shift_y;
  const Vec3 d = cx * right + cy * up + fwd;
  const float len = glm::length(d);
  return Ray{f.origin, d / len, p.clip_start * len, p.clip_end * len};
}

TEST(Camera, WithoutApertureRaysAreBitIdenticalToThePinhole) {
  CameraParams p = turned_camera();
  p.shift_x = 0.1f;
  p.blades = 6;  // ignored while the aperture is closed
  p.aperture_ratio = 2.0f;
  const Camera cam(p, 64, 48, 1.0f, 1.0f);
  EXPECT_FALSE(cam.has_depth_of_field());
  Rng rng(1, 2, 3);
  for (int i = 0; i < 1000; ++i) {
    const float x = 64.0f * rng.next_1d(), y = 48.0f * rng.next_1d();
    const Ray a = cam.generate_ray(x, y, rng.next_2d()), b = previous_pinhole(p, 64, 48, x, y);
    EXPECT_EQ(std::memcmp(&a, &b, sizeof(Ray)), 0) << x << " " << y;
  }
}

// Where a ray crosses the plane at `depth` along the camera's view axis (from the camera plane).
Vec3 at_depth(const Ray& r, const Frame3& f, float depth) {
  const Vec3 fwd = -f.z;
  const float t = (depth - glm::dot(r.origin - f.origin, fwd)) / glm::dot(r.dir, fwd);
  return r.origin + t * r.dir;
}

TEST(Camera, FocusPlaneIsSharpForEveryApertureShape) {
  for (CameraType type : {CameraType::Perspective, CameraType::Orthographic})
    for (int blades : {0, 5, 6})
      for (float ratio : {1.0f, 2.0f}) {
        CameraParams p = turned_camera();
        p.type = type;
        p.aperture_radius = 0.2f;
        p.focus_distance = 4.0f;
        p.blades = blades;
        p.blade_rotation = 0.3f;
        p.aperture_ratio = ratio;
        const Camera cam(p, 80, 60, 1.0f, 1.0f);
        CameraParams pin = p;
        pin.aperture_radius = 0.0f;
        const Camera pinhole(pin, 80, 60, 1.0f, 1.0f);
        const Frame3 f = frame_of(p);
        // ORTHO (as Cycles): the focus plane lies focus_distance beyond the clip_start plane.
        const float focus_depth = type == CameraType::Orthographic ? p.clip_start + 4.0f : 4.0f;
        Rng rng(7, 7, 7);
        for (int pix = 0; pix < 20; ++pix) {
          const float x = 80.0f * rng.next_1d(), y = 60.0f * rng.next_1d();
          const Vec3 sharp = at_depth(pinhole.generate_ray(x, y), f, focus_depth);
          float spread = 0.0f;
          for (int i = 0; i < 200; ++i) {
            const Ray r = cam.generate_ray(x, y, rng.next_2d());
            spread = std::max(spread, glm::length(at_depth(r, f, focus_depth) - sharp));
          }
          EXPECT_LT(spread, 2e-5f) << "type " << int(type) << " blades " << blades << " ratio " << ratio;
        }
      }
}

// Out of focus, the rays through one pixel reach depth d on a copy of the aperture scaled by
// |1 - d / focus| (perspective; thin lens). In pixels, a point at depth d spreads over a circle of
// confusion of radius R |1/d - 1/focus| W / (2 h): with h = sensor / (2 lens) that is the thin-lens
// CoC, diameter 2R lens |d - focus| / (d focus) on a sensor of width `sensor` (focus >> lens).
TEST(Camera, CircleOfConfusionMatchesTheThinLens) {
  const float radius = 0.05f, focus = 3.0f;
  for (float depth : {1.5f, 6.0f, 20.0f})
    for (float ratio : {1.0f, 1.5f}) {
      CameraParams p = turned_camera();
      p.aperture_radius = radius;
      p.focus_distance = focus;
      p.aperture_ratio = ratio;
      const int w = 200, h = 100;
      const Camera cam(p, w, h, 1.0f, 1.0f);
      const Frame3 f = frame_of(p);
      const float scale = std::abs(1.0f - depth / focus);
      // The bundle through the centre pixel, on the plane at `depth`, in camera x/y.
      CameraParams pin = p;
      pin.aperture_radius = 0.0f;
      const Vec3 centre = at_depth(Camera(pin, w, h, 1, 1).generate_ray(100.0f, 50.0f), f, depth);
      float max_x = 0.0f, max_y = 0.0f;
      Rng rng(11, 0, 0);
      for (int i = 0; i < 20000; ++i) {
        const Vec3 d = at_depth(cam.generate_ray(100.0f, 50.0f, rng.next_2d()), f, depth) - centre;
        max_x = std::max(max_x, std::abs(glm::dot(d, f.x)));
        max_y = std::max(max_y, std::abs(glm::dot(d, f.y)));
      }
      EXPECT_NEAR(max_y, radius * scale, 0.01f * radius * scale) << depth;
      EXPECT_NEAR(max_x, radius * scale / ratio, 0.01f * radius * scale / ratio) << depth << " ratio " << ratio;
      // The same in pixels: the point at `depth` on the axis (image centre) reaches the lens point
      // l through the pixel offset by -l (1/d - 1/focus) W / (2h) = -l (1/d - 1/focus) W lens / sensor;
      // the lens edge l = (R / ratio, 0) (u = (1, 0.5) on the concentric disk) is thus coc_px / ratio away.
      const float inv = 1.0f / depth - 1.0f / focus;
      const float coc_px = radius * p.lens_mm * std::abs(inv) * float(w) / p.sensor_width_mm;
      const Vec3 point = f.origin - depth * f.z;
      const float dx = -std::copysign(coc_px / ratio, inv);
      const Ray edge = cam.generate_ray(100.0f + dx, 50.0f, Vec2(0.999999f, 0.5f));
      EXPECT_LT(distance_to_line(point, edge), 1e-4f * depth) << "depth " << depth << " ratio " << ratio;
      EXPECT_GT(distance_to_line(point, cam.generate_ray(100.0f + 1.02f * dx, 50.0f, Vec2(0.999999f, 0.5f))),
                1e-3f * radius * scale);  // and not 2% further out
    }
}

// Upper tail of the chi-square distribution (Wilson-Hilferty).
double p_value(double x, int dof) {
  const double k = dof, z = (std::cbrt(x / k) - (1.0 - 2.0 / (9.0 * k))) / std::sqrt(2.0 / (9.0 * k));
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

bool inside_aperture(const Vec2& q, int blades, float rotation, float ratio) {
  const Vec2 p(q.x * ratio, q.y);
  if (blades < 3) return glm::dot(p, p) <= 1.0f;
  // Inside the regular polygon with corners at rotation + (2k+1) pi / n on the unit circle: the
  // apothem cos(pi/n) bounds the projection on every edge normal (at rotation + 2k pi / n).
  for (int k = 0; k < blades; ++k) {
    const float a = rotation + 2.0f * kPi * float(k) / float(blades);
    if (p.x * std::cos(a) + p.y * std::sin(a) > std::cos(kPi / float(blades))) return false;
  }
  return true;
}

TEST(Camera, ApertureSamplingIsUniformOverTheDiskOrPolygon) {
  struct Shape {
    int blades;
    float rotation, ratio;
  };
  const Shape shapes[] = {{0, 0, 1}, {0, 0, 1.7f}, {3, 0, 1}, {5, 0.4f, 1}, {6, 1.0f, 2.0f}, {8, -0.2f, 1}};
  constexpr int kBins = 16, kSamples = 400000, kSub = 64;
  for (const Shape& s : shapes) {
    const float half_x = 1.0f / s.ratio;
    std::vector<double> observed(kBins * kBins, 0.0), expected(kBins * kBins, 0.0);
    Rng rng(uint32_t(s.blades), 5, 5);
    int outside = 0;
    for (int i = 0; i < kSamples; ++i) {
      const Vec2 q = sample_aperture(rng.next_2d(), s.blades, s.rotation, s.ratio);
      outside += !inside_aperture(q * 0.9999f, s.blades, s.rotation, s.ratio);
      const int bx = std::min(int((q.x / half_x + 1.0f) * 0.5f * kBins), kBins - 1);
      const int by = std::min(int((q.y + 1.0f) * 0.5f * kBins), kBins - 1);
      observed[by * kBins + bx] += 1;
    }
    EXPECT_EQ(outside, 0);
    // Expected: the fraction of each bin's area inside the shape (midpoint sub-cells).
    double total = 0.0;
    for (int by = 0; by < kBins; ++by)
      for (int bx = 0; bx < kBins; ++bx) {
        int in = 0;
        for (int a = 0; a < kSub; ++a)
          for (int b = 0; b < kSub; ++b) {
            const Vec2 q(half_x * (2.0f * (bx + (a + 0.5f) / kSub) / kBins - 1.0f),
                         2.0f * (by + (b + 0.5f) / kSub) / kBins - 1.0f);
            in += inside_aperture(q, s.blades, s.rotation, s.ratio);
          }
        expected[by * kBins + bx] = in;
        total += in;
      }
    double chi2 = 0.0;
    int dof = -1;
    double pooled_o = 0, pooled_e = 0;
    for (int k = 0; k < kBins * kBins; ++k) {
      const double e = expected[k] / total * kSamples;
      if (e < 5.0) {
        pooled_o += observed[k];
        pooled_e += e;
        continue;
      }
      chi2 += sqr(float(observed[k] - e)) / e;
      ++dof;
    }
    if (pooled_e > 5.0) chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e, ++dof;
    const double p = p_value(chi2, dof);
    EXPECT_GT(p, 0.01 / 6) << "blades " << s.blades << " ratio " << s.ratio << " chi2 " << chi2 << " dof " << dof;
    std::printf("aperture blades=%d rotation=%.2f ratio=%.2f: chi2 = %.1f, dof = %d, p = %.3f\n", s.blades, s.rotation,
                s.ratio, chi2, dof, p);
  }
}

TEST(Camera, FstopFollowsBlenderAndBadInputsThrow) {
  EXPECT_FLOAT_EQ(aperture_radius_from_fstop(CameraType::Perspective, 50.0f, 2.8f), 0.05f / 5.6f);
  EXPECT_FLOAT_EQ(aperture_radius_from_fstop(CameraType::Orthographic, 50.0f, 2.0f), 0.25f);
  EXPECT_FLOAT_EQ(aperture_radius_from_fstop(CameraType::Perspective, 50.0f, 0.0f), 0.05f / 2e-5f);  // clamped
  EXPECT_THROW(aperture_radius_from_fstop(CameraType::Perspective, 50.0f, -1.0f), std::invalid_argument);
  auto bad = [](auto change) {
    CameraParams p;
    change(p);
    EXPECT_THROW(Camera(p, 4, 4, 1.0f, 1.0f), std::invalid_argument);
  };
  bad([](CameraParams& p) { p.ortho_scale = 0.0f; });
  bad([](CameraParams& p) { p.aperture_radius = -0.1f; });
  bad([](CameraParams& p) { p.aperture_radius = NAN; });
  bad([](CameraParams& p) { p.aperture_radius = 0.1f, p.focus_distance = 0.0f; });
  bad([](CameraParams& p) { p.blades = -1; });
  bad([](CameraParams& p) { p.aperture_ratio = 0.0f; });
  bad([](CameraParams& p) { p.blade_rotation = INFINITY; });
}

// Light tracing's connection (Camera::connect) inverts generate_ray: the point a ray reaches maps
// back to that ray's raster position, with and without depth of field, and its importance is the
// pixel density of the camera's rays there: pixels per steradian at the lens over distance^2,
// measured from the solid angle generate_ray's rays span around it.
TEST(Camera, ConnectInvertsGenerateRayAndMeasuresItsPixelDensity) {
  for (const float aperture : {0.0f, 0.05f}) {
    CameraParams p = turned_camera();
    p.lens_mm = 35.0f;
    p.shift_x = 0.1f;
    p.aperture_radius = aperture;
    p.focus_distance = 4.0f;
    const int w = 80, h = 60;
    const Camera cam(p, w, h, 1.0f, 1.0f);
    for (const Vec2 raster : {Vec2(40.0f, 30.0f), Vec2(3.5f, 2.25f), Vec2(77.0f, 58.5f)}) {
      const Vec2 lens(0.3f, 0.8f);
      const Ray r = cam.generate_ray(raster.x, raster.y, lens);
      const float t = 7.0f;
      CameraConnection c;
      ASSERT_TRUE(cam.connect(r.origin + t * r.dir, lens, c));
      EXPECT_NEAR(c.x, raster.x, 1e-3f);
      EXPECT_NEAR(c.y, raster.y, 1e-3f);
      EXPECT_NEAR(c.distance, t, 1e-4f);
      // Solid angle of a small raster square about the point, from its corners' rays (same lens point).
      const float e = 0.01f;
      const Vec3 a = cam.generate_ray(raster.x - e, raster.y - e, lens).dir;
      const Vec3 b = cam.generate_ray(raster.x + e, raster.y - e, lens).dir;
      const Vec3 d = cam.generate_ray(raster.x - e, raster.y + e, lens).dir;
      const double solid_angle = glm::length(glm::cross(b - a, d - a));  // parallelogram, tiny
      const double pixels_per_steradian = double(4.0f * e * e) / solid_angle;
      EXPECT_NEAR(c.importance * t * t / pixels_per_steradian, 1.0, 2e-3) << "aperture " << aperture;
    }
  }
  // Behind the camera: no ray.
  CameraConnection c;
  const Camera cam(turned_camera(), 80, 60, 1.0f, 1.0f);
  EXPECT_FALSE(cam.connect(cam.position() - cam.forward(), Vec2(0.5f), c));
}

}  // namespace
}  // namespace torrance
