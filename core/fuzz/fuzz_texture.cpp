// libFuzzer harness: bytes as an image file (the format picked by the first byte) read by the
// core's texture loader (Texture::from_file) and read_image. Each either loads or throws
// std::invalid_argument / std::runtime_error; a header declaring more than the (small) memory
// budget must be refused before any pixel buffer is allocated.
#include "fuzz_common.h"

#include "torrance/film/image_io.h"
#include "torrance/shader/texture.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace torrance;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  torrance_fuzz::set_small_budget();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const char* const kExtensions[] = {".png", ".exr", ".hdr", ".ppm", ".tif", ".bmp", ".jpg", ".tga"};
  if (size < 1) return 0;
  static const std::string dir = [] {
    char tmpl[] = "/tmp/torrance-fuzz-XXXXXX";
    return std::string(mkdtemp(tmpl));
  }();
  const std::string path = dir + "/input" + kExtensions[data[0] % 8];
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  torrance_fuzz::clearly([&] {
    const ImageData image = read_image(path);
    if (image.pixels.size() != size_t(image.width) * image.height * image.channels)
      torrance_fuzz::fail("read_image: pixel count differs from width x height x channels");
  });
  torrance_fuzz::clearly([&] {
    const Texture t = Texture::from_file(path, data[0] & 8 ? ColorSpace::SRGB : ColorSpace::Linear,
                                         Interpolation::Linear);
    for (float u : {0.0f, 0.3f, -7.5f, 1e30f, NAN})
      for (float footprint : {0.0f, 0.01f, 1e9f})
        for (float v : {t.lookup(Vec2(u, 0.5f), footprint).x, t.lookup(Vec2(0.25f, u), footprint).w})
          if (!std::isfinite(v)) torrance_fuzz::fail("texture lookup gave a non-finite value");
  });
  std::remove(path.c_str());
  return 0;
}
