#include "torrance/shader/texture.h"

#include "torrance/shader/cubic_bspline.h"

#include "torrance/film/image_io.h"
#include "torrance/util/limits.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <stdexcept>

namespace torrance {
namespace {
constexpr float kMaxTexelValue = 1e20f;

float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}
// sRGB-decoded colour, kept within the texel bound (decoding raises large encoded values to ^2.4).
glm::vec4 decoded(const glm::vec4& t) {
  const glm::vec4 d(srgb_to_linear(t.r), srgb_to_linear(t.g), srgb_to_linear(t.b), t.a);
  return glm::min(d, glm::vec4(kMaxTexelValue));
}
// decoded() through a table for encoded values in [0, 1] (linear between 4096 steps: within
// 1e-7 of the formula), the formula elsewhere: building the mip pyramid decodes 16 lookups a
// coarse texel.
glm::vec4 decoded_fast(const glm::vec4& t) {
  static constexpr int kSteps = 4096;
  static const std::vector<float> table = [] {
    std::vector<float> v(kSteps + 2);
    for (int i = 0; i <= kSteps + 1; ++i) v[i] = srgb_to_linear(float(std::min(i, kSteps)) / kSteps);
    return v;
  }();
  glm::vec4 out = t;
  for (int c = 0; c < 3; ++c) {
    if (!(t[c] >= 0.0f && t[c] <= 1.0f)) {
      out[c] = std::min(srgb_to_linear(t[c]), kMaxTexelValue);
      continue;
    }
    const float x = t[c] * kSteps;
    const int i = int(x);
    out[c] = table[i] + (x - float(i)) * (table[i + 1] - table[i]);
  }
  return out;
}
int mirror(int i, int n) {
  const int m = std::abs(i + (i < 0 ? 1 : 0)) % (2 * n);
  return m >= n ? 2 * n - m - 1 : m;
}
int wrap(int i, int n) {
  const int m = i % n;
  return m < 0 ? m + n : m;
}
}  // namespace

Texture::Texture(int width, int height, int channels, const float* pixels, ColorSpace space,
                 Interpolation interpolation)
    : width_(width), height_(height), interpolation_(interpolation), srgb_(space == ColorSpace::SRGB) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("texture size must be positive");
  if (channels < 1 || channels > 4) throw std::invalid_argument("texture must have 1 to 4 channels");
  if (size_t(width) * height > (size_t(1) << 28)) throw std::invalid_argument("texture is too large");
  require_memory(double(width) * double(height) * kBytesPerTexel,
                 "a " + std::to_string(width) + " x " + std::to_string(height) + " texture");
  std::vector<glm::vec4> texels(size_t(width) * height);
  for (size_t i = 0; i < texels.size(); ++i) {
    const float* p = pixels + i * channels;
    glm::vec4 t(0.0f, 0.0f, 0.0f, 1.0f);
    if (channels <= 2) t = glm::vec4(p[0], p[0], p[0], channels == 2 ? p[1] : 1.0f);
    else for (int c = 0; c < channels; ++c) t[c] = p[c];
    for (int c = 0; c < 4; ++c)
      if (!std::isfinite(t[c])) t[c] = 0.0f;  // a broken pixel must not poison the render
    // Finite is not enough: bilinear filtering (a + t (b - a)) and the mip levels' sums overflow
    // to Inf and then NaN near float's limit (3e38 next to -3e38); far above any real radiance.
    texels[i] = glm::clamp(t, glm::vec4(-kMaxTexelValue), glm::vec4(kMaxTexelValue));
  }
  levels_.push_back({width, height, std::move(texels)});
  while (levels_.back().width > 1 || levels_.back().height > 1) {  // 2x2 box-filtered mip levels
    const Level& fine = levels_.back();
    Level coarse{std::max(fine.width / 2, 1), std::max(fine.height / 2, 1), {}};
    coarse.texels.resize(size_t(coarse.width) * coarse.height);
    if (srgb_ && levels_.size() == 1) {
      average_decoded(fine, coarse);
    } else {
      for (int y = 0; y < coarse.height; ++y)
        for (int x = 0; x < coarse.width; ++x) {
          const int x0 = std::min(2 * x, fine.width - 1), x1 = std::min(2 * x + 1, fine.width - 1);
          const int y0 = std::min(2 * y, fine.height - 1), y1 = std::min(2 * y + 1, fine.height - 1);
          coarse.texels[size_t(y) * coarse.width + x] =
              0.25f * (fine.texel(x0, y0) + fine.texel(x1, y0) + fine.texel(x0, y1) + fine.texel(x1, y1));
        }
    }
    levels_.push_back(std::move(coarse));
  }
}

// The first coarse level of an sRGB image: each texel the mean of what a lookup of the finest
// level gives over its area (interpolated in sRGB, then decoded), not the mean of the decoded
// texels; they differ wherever neighbouring texels differ (the sRGB ramp between a light and a
// dark texel is darker than the linear one: a checker's mean came out 2 % bright). Sampled at 4 x 4
// points placed so that, over the image, every cell between texel centres is integrated by the
// 2-point Gauss rule in each direction (a checker of 10 squares in 256 px: mean 0.26504, a dense
// integration 0.26500, the decoded texels' mean 0.27019).
void Texture::average_decoded(const Level& fine, Level& coarse) {
  const float sx = float(fine.width) / float(coarse.width), sy = float(fine.height) / float(coarse.height);
  constexpr float kGauss = 0.28867513f;  // 1 / (2 sqrt 3)
  const float q[4] = {0.5f * kGauss, 0.5f - 0.5f * kGauss, 0.5f + 0.5f * kGauss, 1.0f - 0.5f * kGauss};
  tbb::parallel_for(0, coarse.height, [&](int y) {
    for (int x = 0; x < coarse.width; ++x) {
      glm::vec4 sum(0.0f);
      for (float qy : q)
        for (float qx : q) {
          const Vec2 uv((float(x) + qx) * sx / float(fine.width), (float(y) + qy) * sy / float(fine.height));
          sum += decoded_fast(fine.bilinear(uv));
        }
      coarse.texels[size_t(y) * coarse.width + x] = sum / 16.0f;
    }
  });
}

Texture Texture::from_file(const std::string& path, ColorSpace space, Interpolation interpolation) {
  const ImageData data = read_image(path, 4.0 * 4 + kBytesPerTexel);  // + the flipped copy + the texels
  const int channels = std::min(data.channels, 4);
  std::vector<float> flipped(size_t(data.width) * data.height * channels);
  for (int y = 0; y < data.height; ++y)
    for (int x = 0; x < data.width; ++x)
      for (int c = 0; c < channels; ++c)
        flipped[(size_t(data.height - 1 - y) * data.width + x) * channels + c] =
            data.pixels[(size_t(y) * data.width + x) * data.channels + c];
  return Texture(data.width, data.height, channels, flipped.data(), space, interpolation);
}

glm::vec4 Texture::Level::texel(int x, int y, Extension e) const {
  switch (e) {
    case Extension::Repeat: break;
    case Extension::Extend:
      x = std::clamp(x, 0, width - 1);
      y = std::clamp(y, 0, height - 1);
      break;
    case Extension::Clip:
      if (x < 0 || y < 0 || x >= width || y >= height) return glm::vec4(0.0f);
      break;
    case Extension::Mirror:
      x = mirror(x, width);
      y = mirror(y, height);
      break;
  }
  return texels[size_t(wrap(y, height)) * width + wrap(x, width)];
}

glm::vec4 Texture::Level::bilinear(const Vec2& uv, Extension e) const {
  // Repeat: the UV's fraction (exact for huge UVs); the others: the UV as it is, clamped to a
  // range where the texel arithmetic stays in int (far outside, Extend/Mirror/Clip are constant or
  // periodic anyway).
  const Vec2 at = e == Extension::Repeat ? uv - glm::floor(uv) : glm::clamp(uv, Vec2(-1e6f), Vec2(1e6f));
  const float x = at.x * width - 0.5f, y = at.y * height - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float tx = x - float(x0), ty = y - float(y0);
  return glm::mix(glm::mix(texel(x0, y0, e), texel(x0 + 1, y0, e), tx),
                  glm::mix(texel(x0, y0 + 1, e), texel(x0 + 1, y0 + 1, e), tx), ty);
}

glm::vec4 Texture::Level::bicubic(const Vec2& uv, Extension e) const {
  const Vec2 at = e == Extension::Repeat ? uv - glm::floor(uv) : glm::clamp(uv, Vec2(-1e6f), Vec2(1e6f));
  const float x = at.x * width - 0.5f, y = at.y * height - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const std::array<float, 4> wx = cubic_bspline_weights(x - float(x0)),
                               wy = cubic_bspline_weights(y - float(y0));
  glm::vec4 sum(0.0f);
  for (int j = 0; j < 4; ++j) {
    glm::vec4 row(0.0f);
    for (int i = 0; i < 4; ++i) row += wx[size_t(i)] * texel(x0 - 1 + i, y0 - 1 + j, e);
    sum += wy[size_t(j)] * row;
  }
  return sum;
}

glm::vec4 Texture::lookup(const Vec2& uv, float footprint, Extension extension) const {
  // The finest level holds the texels as stored, so an sRGB image is interpolated in sRGB and
  // decoded after, as Cycles does with the sRGB images it keeps compressed (all of them); the
  // coarser levels are linear.
  const Level& base = levels_[0];
  auto finest = [&](const glm::vec4& t) { return srgb_ ? decoded(t) : t; };
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return finest(base.texel(0, 0));
  // Level of detail: log2 of the footprint in texels of the finest level.
  const float texels = std::isfinite(footprint) ? footprint * float(std::max(width_, height_)) : 0.0f;
  if (texels <= 1.0f) {
    if (interpolation_ == Interpolation::Closest) {
      if (extension == Extension::Clip && (uv.x < 0.0f || uv.y < 0.0f || uv.x > 1.0f || uv.y > 1.0f))
        return glm::vec4(0.0f);
      const Vec2 at = extension == Extension::Repeat ? uv - glm::floor(uv) : glm::clamp(uv, Vec2(-1e6f), Vec2(1e6f));
      return finest(base.texel(int(std::floor(at.x * width_)), int(std::floor(at.y * height_)), extension));
    }
    return finest(interpolation_ == Interpolation::Cubic ? base.bicubic(uv, extension) : base.bilinear(uv, extension));
  }
  const float lod = std::min(std::log2(texels), float(levels_.size() - 1));
  const int l0 = int(lod);
  const int l1 = std::min(l0 + 1, int(levels_.size()) - 1);
  const float t = lod - float(l0);
  const glm::vec4 fine = l0 == 0 ? finest(base.bilinear(uv, extension)) : levels_[l0].bilinear(uv, extension);
  return glm::mix(fine, levels_[l1].bilinear(uv, extension), t);
}

}  // namespace torrance
