// Image files through OpenImageIO: EXR (and HDR/TIFF) keep linear floats; PNG/JPEG get sRGB 8-bit.
#pragma once

#include "torrance/integrator/integrator.h"

#include <string>

namespace torrance {

void write_image(const std::string& path, const Image& image);  // throws std::runtime_error
// Reads any OIIO format as linear float; channels() tells how many per pixel.
struct ImageData {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;
};
// The header is checked before any pixel is read: a size the file cannot have, or one whose
// floats (plus extra_bytes_per_pixel the caller will add) exceed the memory budget, is refused.
ImageData read_image(const std::string& path, double extra_bytes_per_pixel = 0.0, int subimage = 0);

inline float linear_to_srgb(float x) {
  x = std::min(std::max(x, 0.0f), 1.0f);
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

}  // namespace torrance
