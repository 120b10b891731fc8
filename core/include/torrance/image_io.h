// Image files through OpenImageIO: EXR (and HDR/TIFF) keep linear floats; PNG/JPEG get sRGB 8-bit.
#pragma once

#include "torrance/integrator.h"

#include <string>

namespace torrance {

void write_image(const std::string& path, const Image& image);  // throws std::runtime_error
// Reads any OIIO format as linear float; channels() tells how many per pixel.
struct ImageData {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;
};
ImageData read_image(const std::string& path);

inline float linear_to_srgb(float x) {
  x = std::min(std::max(x, 0.0f), 1.0f);
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

}  // namespace torrance
