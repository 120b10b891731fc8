#include "torrance/lights/environment.h"

#include "torrance/util/sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

namespace torrance {
namespace {

// Index of the interval of a CDF (size n + 1, cdf[0] = 0, cdf[n] = 1) containing x, and the
// position within it.
int find_interval(const float* cdf, int n, float x, float& t) {
  const int i = std::clamp(int(std::upper_bound(cdf, cdf + n + 1, x) - cdf) - 1, 0, n - 1);
  const float span = cdf[i + 1] - cdf[i];
  t = span > 0.0f ? std::clamp((x - cdf[i]) / span, 0.0f, 1.0f) : 0.5f;
  return i;
}

}  // namespace

Vec2 EnvironmentMap::direction_to_uv(const Vec3& dir) {
  return Vec2(0.5f - std::atan2(dir.y, dir.x) / kTwoPi, 1.0f - std::acos(std::clamp(dir.z, -1.0f, 1.0f)) / kPi);
}

Vec3 EnvironmentMap::uv_to_direction(const Vec2& uv) {
  const float phi = kTwoPi * (0.5f - uv.x), theta = kPi * (1.0f - uv.y);
  const float s = std::sin(theta);
  return Vec3(s * std::cos(phi), s * std::sin(phi), std::cos(theta));
}

EnvironmentMap::EnvironmentMap(std::shared_ptr<const Texture> image, float strength)
    : image_(std::move(image)), strength_(strength) {
  if (!image_) throw std::invalid_argument("environment map needs an image");
  if (!std::isfinite(strength)) throw std::invalid_argument("world strength must be finite");
  width_ = image_->width();
  height_ = image_->height();
  std::vector<float> lum(size_t(width_) * height_);
  for (int j = 0; j < height_; ++j)
    for (int i = 0; i < width_; ++i)
      lum[size_t(j) * width_ + i] = luminance(Vec3(image_->lookup(Vec2((i + 0.5f) / width_, (j + 0.5f) / height_))));
  build(std::move(lum));
  average_luminance_ *= std::abs(strength_);  // a negative strength takes light away: chosen by magnitude
}

EnvironmentMap::EnvironmentMap(std::shared_ptr<const EmissionShader> shader, int resolution)
    : shader_(std::move(shader)) {
  if (!shader_) throw std::invalid_argument("environment map needs a background shader");
  if (resolution < 4 || resolution > 16384)
    throw std::invalid_argument("the world's map resolution must be in [4, 16384], not " + std::to_string(resolution));
  width_ = resolution;
  height_ = std::max(resolution / 2, 2);
  // As Cycles bakes its background map: the shader at each cell's centre, seen by no ray in
  // particular (kRayEmission).
  PathState baking;
  baking.ray_flags = kRayEmission;
  std::vector<float> lum(size_t(width_) * height_);
  tbb::parallel_for(0, height_, [&](int j) {
    for (int i = 0; i < width_; ++i) {
      const Vec3 dir = uv_to_direction(Vec2((i + 0.5f) / width_, (j + 0.5f) / height_));
      lum[size_t(j) * width_ + i] = luminance(shader_->background(dir, baking));
    }
  });
  build(std::move(lum));
}

EnvironmentMap::EnvironmentMap(std::shared_ptr<const EmissionShader> shader, int resolution, const SunGuide& sun)
    : EnvironmentMap(std::move(shader), std::max(resolution, 512)) {
  const float length = glm::length(sun.direction);
  if (!(length > 0.0f) || !std::isfinite(length) || !(sun.half_angle > 0.0f) || !(sun.half_angle < kPi))
    throw std::invalid_argument("a sun guide needs a direction and a half angle in (0, pi)");
  sun_axis_ = sun.direction / length;
  sun_one_minus_cos_ = 2.0f * std::sin(0.5f * sun.half_angle) * std::sin(0.5f * sun.half_angle);
  share_sun_ = 4.0f / 5.0f;  // Cycles' sun weight 4 against the map's 1
}

void EnvironmentMap::build(std::vector<float> lum) {
  // Cell (i, j) covers u in [i, i+1)/W and v in [j, j+1)/H; its weight is its luminance times
  // sin(theta) (the solid angle it spans), with a floor so no direction is impossible. Negative
  // light (a world taking light away) is sampled by its magnitude, as negative lamps are.
  std::vector<float>& weight = lum;
  double total = 0.0, lum_sum = 0.0, solid_sum = 0.0;
  for (int j = 0; j < height_; ++j) {
    const float sin_theta = std::sin(kPi * (1.0f - (j + 0.5f) / height_));
    for (int i = 0; i < width_; ++i) {
      float& w = weight[size_t(j) * width_ + i];
      const float l = std::isfinite(w) ? std::abs(w) : 0.0f;
      w = l * sin_theta;
      lum_sum += double(l) * sin_theta;
      solid_sum += sin_theta;
    }
  }
  average_luminance_ = solid_sum > 0 ? float(lum_sum / solid_sum) : 0.0f;
  const double mean = lum_sum / std::max(double(weight.size()), 1.0);
  for (float& w : weight) {
    w += float(0.01 * mean) + 1e-12f;
    total += w;
  }
  column_cdf_.assign(size_t(height_) * (width_ + 1), 0.0f);
  row_cdf_.assign(height_ + 1, 0.0f);
  cell_pdf_.resize(weight.size());
  std::vector<double> row_sum(height_, 0.0);
  for (int j = 0; j < height_; ++j) {
    double run = 0.0;
    for (int i = 0; i < width_; ++i) run += weight[size_t(j) * width_ + i];
    row_sum[j] = run;
    double acc = 0.0;
    for (int i = 0; i < width_; ++i) {
      acc += weight[size_t(j) * width_ + i];
      column_cdf_[size_t(j) * (width_ + 1) + i + 1] = float(acc / run);
    }
  }
  double acc = 0.0;
  for (int j = 0; j < height_; ++j) {
    acc += row_sum[j];
    row_cdf_[j + 1] = float(acc / total);
  }
  for (size_t k = 0; k < weight.size(); ++k) cell_pdf_[k] = float(weight[k] / total * double(weight.size()));
}

Vec3 EnvironmentMap::radiance(const Vec3& dir, const PathState& state) const {
  if (shader_) return shader_->background(dir, state);
  return Vec3(image_->lookup(direction_to_uv(dir))) * strength_;
}

Vec3 EnvironmentMap::sample(const Vec2& u, float& pdf) const {
  Vec2 v = u;
  if (share_sun_ > 0.0f) {
    if (u.x < share_sun_) {
      v.x = u.x / share_sun_;
      const Vec3 dir = Frame(sun_axis_).to_world(sample_uniform_cone(v, sun_one_minus_cos_));
      pdf = this->pdf(dir);
      return dir;
    }
    v.x = (u.x - share_sun_) / (1.0f - share_sun_);
  }
  float tv, tu;
  const int j = find_interval(row_cdf_.data(), height_, v.y, tv);
  const int i = find_interval(&column_cdf_[size_t(j) * (width_ + 1)], width_, v.x, tu);
  const Vec2 uv((i + tu) / width_, (j + tv) / height_);
  const Vec3 dir = uv_to_direction(uv);
  if (share_sun_ > 0.0f) {
    pdf = this->pdf(dir);
    return dir;
  }
  const float sin_theta = std::sin(kPi * (1.0f - uv.y));
  pdf = sin_theta > 1e-7f ? cell_pdf_[size_t(j) * width_ + i] / (2.0f * kPi * kPi * sin_theta) : 0.0f;
  return dir;
}

float EnvironmentMap::grid_pdf(const Vec3& dir) const {
  const Vec2 uv = direction_to_uv(dir);
  const int i = std::clamp(int(uv.x * width_), 0, width_ - 1), j = std::clamp(int(uv.y * height_), 0, height_ - 1);
  const float sin_theta = safe_sqrt(1.0f - dir.z * dir.z);
  return sin_theta > 1e-7f ? cell_pdf_[size_t(j) * width_ + i] / (2.0f * kPi * kPi * sin_theta) : 0.0f;
}

float EnvironmentMap::pdf(const Vec3& dir) const {
  if (share_sun_ <= 0.0f) return grid_pdf(dir);
  // In the cone: 1 - cos(angle to the axis) <= 1 - cos(half angle), measured without cancellation.
  const float chord = glm::length(dir - sun_axis_);
  const float in_cone = 0.5f * chord * chord <= sun_one_minus_cos_ ? 1.0f / cone_solid_angle(sun_one_minus_cos_) : 0.0f;
  return share_sun_ * in_cone + (1.0f - share_sun_) * grid_pdf(dir);
}

}  // namespace torrance
