#include "torrance/texture.h"

#include "torrance/image_io.h"

#include <stdexcept>

namespace torrance {
namespace {
float srgb_to_linear(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}
int wrap(int i, int n) {
  const int m = i % n;
  return m < 0 ? m + n : m;
}
}  // namespace

Texture::Texture(int width, int height, int channels, const float* pixels, ColorSpace space,
                 Interpolation interpolation)
    : width_(width), height_(height), interpolation_(interpolation) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("texture size must be positive");
  if (channels < 1 || channels > 4) throw std::invalid_argument("texture must have 1 to 4 channels");
  texels_.resize(size_t(width) * height);
  for (size_t i = 0; i < texels_.size(); ++i) {
    const float* p = pixels + i * channels;
    glm::vec4 t(0.0f, 0.0f, 0.0f, 1.0f);
    if (channels <= 2) t = glm::vec4(p[0], p[0], p[0], channels == 2 ? p[1] : 1.0f);
    else for (int c = 0; c < channels; ++c) t[c] = p[c];
    for (int c = 0; c < 4; ++c)
      if (!std::isfinite(t[c])) t[c] = 0.0f;  // a broken pixel must not poison the render
    if (space == ColorSpace::SRGB)
      for (int c = 0; c < 3; ++c) t[c] = srgb_to_linear(t[c]);
    texels_[i] = t;
  }
}

Texture Texture::from_file(const std::string& path, ColorSpace space, Interpolation interpolation) {
  const ImageData data = read_image(path);
  const int channels = std::min(data.channels, 4);
  std::vector<float> flipped(size_t(data.width) * data.height * channels);
  for (int y = 0; y < data.height; ++y)
    for (int x = 0; x < data.width; ++x)
      for (int c = 0; c < channels; ++c)
        flipped[(size_t(data.height - 1 - y) * data.width + x) * channels + c] =
            data.pixels[(size_t(y) * data.width + x) * data.channels + c];
  return Texture(data.width, data.height, channels, flipped.data(), space, interpolation);
}

glm::vec4 Texture::texel(int x, int y) const { return texels_[size_t(wrap(y, height_)) * width_ + wrap(x, width_)]; }

glm::vec4 Texture::lookup(const Vec2& uv) const {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return texel(0, 0);
  const float fx = (uv.x - std::floor(uv.x)) * width_, fy = (uv.y - std::floor(uv.y)) * height_;
  if (interpolation_ == Interpolation::Closest) return texel(int(fx), int(fy));
  const float x = fx - 0.5f, y = fy - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float tx = x - float(x0), ty = y - float(y0);
  return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), tx), glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), tx),
                  ty);
}

}  // namespace torrance
