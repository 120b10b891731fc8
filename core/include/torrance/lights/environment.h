// A world whose radiance varies with direction, importance-sampled by a piecewise-constant
// density over an equirectangular grid (u = 0.5 - atan2(y, x) / 2 pi, v = 1 - acos(z) / pi, as
// Cycles' Environment Texture maps directions), proportional to luminance * sin(theta), with a
// floor so that no direction is impossible:
//  * an HDRI: an equirectangular image times a strength, the grid its pixels;
//  * a background shader (emission_shader.h): the world's node graph, the grid its radiance at
//    the cells' centres (Cycles' world Map Resolution), the radiance itself run per direction;
//    with a sun disc in it (a Sky Texture's), sampled as Cycles' sun guiding does: 4 of 5
//    samples uniformly in the disc's cone, 1 of 5 from the grid (one density, the mixture).
#pragma once

#include "torrance/lights/emission_shader.h"
#include "torrance/shader/texture.h"

#include <memory>
#include <vector>

namespace torrance {

// A sun disc in the world: its centre's unit direction and angular radius (radians).
struct SunGuide {
  Vec3 direction{0.0f, 0.0f, 1.0f};
  float half_angle = 0.0f;
};

class EnvironmentMap {
 public:
  EnvironmentMap(std::shared_ptr<const Texture> image, float strength);
  // resolution: the grid's width (its height is half of it), at least 4.
  EnvironmentMap(std::shared_ptr<const EmissionShader> shader, int resolution);
  // The same, sampling the sun's cone too (Cycles' sun guiding; the grid at least 512 wide).
  EnvironmentMap(std::shared_ptr<const EmissionShader> shader, int resolution, const SunGuide& sun);

  // state: the ray's (a background shader reads it; NEE: kRayEmission).
  Vec3 radiance(const Vec3& dir, const PathState& state = {}) const;
  // A direction with probability density pdf (solid angle) roughly proportional to radiance.
  Vec3 sample(const Vec2& u, float& pdf) const;
  float pdf(const Vec3& dir) const;
  // The mean over the sphere of the grid's luminance (0: the world is black where sampled).
  float average_luminance() const { return average_luminance_; }
  bool reads_path() const { return shader_ && shader_->reads_path(); }

  static Vec2 direction_to_uv(const Vec3& dir);
  static Vec3 uv_to_direction(const Vec2& uv);

 private:
  // Builds the density from each cell's luminance (row-major, width_ x height_).
  void build(std::vector<float> luminance);
  float grid_pdf(const Vec3& dir) const;

  std::shared_ptr<const Texture> image_;
  float strength_ = 1.0f;
  std::shared_ptr<const EmissionShader> shader_;
  int width_ = 0, height_ = 0;       // of the sampling grid
  std::vector<float> row_cdf_;       // height_ + 1 entries, over v
  std::vector<float> column_cdf_;    // height_ rows of width_ + 1 entries, over u within a row
  std::vector<float> cell_pdf_;      // density in (u, v) per cell
  float average_luminance_ = 0.0f;
  // Sun guiding: the cone's axis and 1 - cos(half angle); share_sun_ of the samples (0: none).
  Vec3 sun_axis_{0.0f, 0.0f, 1.0f};
  float sun_one_minus_cos_ = 0.0f;
  float share_sun_ = 0.0f;
};

}  // namespace torrance
