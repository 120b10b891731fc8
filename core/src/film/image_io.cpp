#include "torrance/film/image_io.h"

#include "torrance/util/limits.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace torrance {
namespace {
std::string lower_extension(const std::string& path) {
  const auto dot = path.rfind('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}
}  // namespace

void write_image(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 || image.rgba.size() != size_t(image.width) * image.height * 4)
    throw std::invalid_argument("write_image: image must be a non-empty (height, width, 4) array");
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error("cannot write '" + path + "': " + OIIO::geterror());
  const std::string ext = lower_extension(path);
  const bool linear = ext == "exr" || ext == "hdr" || ext == "tif" || ext == "tiff" || ext == "pfm";
  const int channels = (ext == "jpg" || ext == "jpeg") ? 3 : 4;
  OIIO::ImageSpec spec(image.width, image.height, channels, linear ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (!out->open(path, spec)) throw std::runtime_error("cannot open '" + path + "': " + out->geterror());
  bool ok;
  if (linear) {
    ok = out->write_image(OIIO::TypeDesc::FLOAT, image.rgba.data());
  } else {
    std::vector<uint8_t> bytes(size_t(image.width) * image.height * channels);
    for (size_t i = 0, n = size_t(image.width) * image.height; i < n; ++i)
      for (int c = 0; c < channels; ++c) {
        const float v = image.rgba[4 * i + c];
        const float encoded = c < 3 ? linear_to_srgb(v) : std::min(std::max(v, 0.0f), 1.0f);
        bytes[i * channels + c] = uint8_t(std::lround(encoded * 255.0f));
      }
    ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
  }
  if (!ok || !out->close()) throw std::runtime_error("failed writing '" + path + "': " + out->geterror());
}

ImageData read_image(const std::string& path, double extra_bytes_per_pixel, int subimage) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error("cannot read '" + path + "': " + OIIO::geterror());
  if (subimage != 0 && !in->seek_subimage(subimage, 0))
    throw std::runtime_error("cannot read '" + path + "': no subimage " + std::to_string(subimage));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1 || spec.nchannels <= 0 || spec.deep)
    throw std::runtime_error("cannot read '" + path + "': unsupported image size " + std::to_string(spec.width) + " x " +
                             std::to_string(spec.height) + " x " + std::to_string(spec.depth) + ", " +
                             std::to_string(spec.nchannels) + " channels" + (spec.deep ? " (deep)" : ""));
  require_memory(double(spec.width) * double(spec.height) * (4.0 * spec.nchannels + extra_bytes_per_pixel),
                 "reading the " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " image '" +
                     path + "'");
  ImageData data;
  data.width = spec.width;
  data.height = spec.height;
  data.channels = spec.nchannels;
  data.pixels.resize(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(subimage, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.pixels.data()))
    throw std::runtime_error("failed reading '" + path + "': " + in->geterror());
  in->close();
  return data;
}

}  // namespace torrance
