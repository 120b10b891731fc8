// Image textures as Blender's Image Texture node samples them: UV (0,0) is the image's bottom-left
// corner, REPEAT extension, Linear (bilinear), Closest or Cubic interpolation. sRGB-encoded images are
// interpolated as stored and decoded after (as Cycles, which keeps sRGB images compressed), so
// an edge between two colours ramps in sRGB, not in linear. A mip pyramid (2x2 box filter) lets lookups
// with a footprint average what a pixel covers (trilinear), so distant detail does not alias.
#pragma once

#include "torrance/util/math.h"

#include <string>
#include <vector>

namespace torrance {

enum class ColorSpace { Linear, SRGB };
// Cubic: Cycles' CPU bicubic, a uniform cubic B-spline over 4 x 4 texels (Smart renders as it).
enum class Interpolation { Linear, Closest, Cubic };
// The Image Texture node's Extension, as Cycles' CPU lookups: Repeat wraps; Extend clamps to the
// edge texels; Clip reads 0 outside the image (Linear: texels beyond the edge are 0; Closest: 0
// outside [0, 1]); Mirror (Blender 3.5+) reflects at each edge.
enum class Extension { Repeat, Extend, Clip, Mirror };

class Texture {
 public:
  // pixels: width * height * channels floats, row 0 = BOTTOM (Blender's Image.pixels order).
  Texture(int width, int height, int channels, const float* pixels, ColorSpace space, Interpolation interpolation);
  // Loads any file OpenImageIO reads (row 0 = top in the file; flipped to Blender's order).
  static Texture from_file(const std::string& path, ColorSpace space, Interpolation interpolation);

  // RGBA; a grey image gives (v, v, v, 1). footprint: the size, in UV units, of the area to
  // average (0 = the finest level, as Blender's node without filtering).
  glm::vec4 lookup(const Vec2& uv, float footprint = 0.0f, Extension extension = Extension::Repeat) const;
  // Memory per pixel of the image: RGBA float texels and their mip pyramid (a third more).
  static constexpr double kBytesPerTexel = 16.0 * 4.0 / 3.0;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Level {
    int width, height;
    std::vector<glm::vec4> texels;
    glm::vec4 texel(int x, int y, Extension e = Extension::Repeat) const;
    glm::vec4 bilinear(const Vec2& uv, Extension e = Extension::Repeat) const;
    glm::vec4 bicubic(const Vec2& uv, Extension e = Extension::Repeat) const;
  };
  static void average_decoded(const Level& fine, Level& coarse);
  int width_, height_;
  Interpolation interpolation_;
  bool srgb_;                  // levels_[0] holds sRGB-encoded colours (the coarser levels: linear)
  std::vector<Level> levels_;  // levels_[0] = the image
};

// The scene-linear luminance Blender uses to turn a colour into a float socket value.
inline float blender_luminance(const Vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

}  // namespace torrance
