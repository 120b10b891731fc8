// What each render pass takes from a camera sample (PathRadiance) and how the film's per-pixel
// means become the pass Blender shows, as Cycles 3.4 writes and reads them (kernel/film/).
#pragma once

#include "integrator/path_tracer.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace torrance {

// The passes a set of passes needs accumulated besides itself: the Diffuse and Glossy light
// passes are divided by Diffuse and Glossy Color.
inline uint32_t pass_dependencies(uint32_t passes) {
  return ((passes & (kPassDiffuseDirect | kPassDiffuseIndirect)) ? uint32_t(kPassAlbedo) : 0u) |
         ((passes & (kPassGlossyDirect | kPassGlossyIndirect)) ? uint32_t(kPassGlossyColor) : 0u) |
         ((passes & kPassVector) ? uint32_t(kPassVectorWeight) : 0u);
}

// The colour pass a light pass is divided by (0: none).
inline Pass divisor_of(Pass pass) {
  switch (pass) {
    case kPassDiffuseDirect:
    case kPassDiffuseIndirect: return kPassAlbedo;
    case kPassGlossyDirect:
    case kPassGlossyIndirect: return kPassGlossyColor;
    default: return Pass(0);
  }
}

// Depth, Position, Object Index and Material Index of the ray through the pixel's centre
// (data_passes.cpp) into r: Cycles' first sample.
void first_sample_data(const PathContext& ctx, Ray ray, PathRadiance& r);

inline float pass_scalar(Pass pass, const PathRadiance& r) {
  switch (pass) {
    case kPassMist: return r.mist;
    case kPassObjectIndex: return r.object_index;
    case kPassMaterialIndex: return r.material_index;
    case kPassDenoisingDepth: return r.denoising_depth;
    case kPassVectorWeight: return r.motion_weight;
    default: return r.depth;
  }
}

inline Vec3 pass_color(Pass pass, const PathRadiance& r) {
  switch (pass) {
    case kPassNormal: return r.normal;
    case kPassAlbedo: return r.albedo;
    case kPassDiffuseDirect: return r.diffuse_direct;
    case kPassDiffuseIndirect: return r.diffuse_indirect;
    case kPassGlossyDirect: return r.glossy_direct;
    case kPassGlossyIndirect: return r.glossy_indirect;
    case kPassGlossyColor: return r.glossy_color;
    case kPassEmission: return r.emission;
    case kPassEnvironment: return r.environment;
    case kPassUV: return r.uv;
    case kPassAO: return r.ao;
    case kPassPosition: return r.position;
    case kPassDenoisingAlbedo: return r.denoising_albedo;
    case kPassDenoisingNormal: return r.denoising_normal;
    default: return Vec3(0.0f);
  }
}

// The passes of 4 channels.
inline glm::vec4 pass_quad(Pass pass, const PathRadiance& r) { return pass == kPassVector ? r.motion : glm::vec4(0.0f); }

// a / b per channel, 0 where b is 0, and there the mean of the channels that could be divided
// (Cycles' safe_divide_even_color: a grey rather than a hue where the colour has a 0).
inline Vec3 divide_even_color(const Vec3& a, const Vec3& b) {
  Vec3 q;
  int defined = 0;
  float sum = 0.0f;
  for (int c = 0; c < 3; ++c) {
    q[c] = b[c] != 0.0f ? a[c] / b[c] : 0.0f;
    if (b[c] != 0.0f) {
      ++defined;
      sum += q[c];
    }
  }
  if (defined == 1 || defined == 2)
    for (int c = 0; c < 3; ++c)
      if (b[c] == 0.0f) q[c] = sum / float(defined);
  return q;
}

// The pass Blender shows from the film's per-pixel means of the accumulated passes: the Mist
// pass is 1 - the mean of (1 - mist) (clamped to [0, 1]); the Diffuse and Glossy Direct/Indirect
// means are divided by Diffuse and Glossy Color's, the Vector pass by the share of samples that
// wrote one (Cycles' motion weight; 0 where none did); the others as they are.
inline Image finish_pass(Pass pass, const std::vector<std::pair<Pass, Image>>& resolved) {
  auto find = [&](Pass p) -> const Image& {
    return std::find_if(resolved.begin(), resolved.end(), [&](const auto& e) { return e.first == p; })->second;
  };
  Image img = find(pass);
  if (pass == kPassMist) {
    for (float& v : img.rgba) v = std::clamp(1.0f - v, 0.0f, 1.0f);
  } else if (pass == kPassVector) {
    const Image& weight = find(kPassVectorWeight);
    for (size_t i = 0; i < weight.rgba.size(); ++i) {
      const float w = weight.rgba[i];
      for (int c = 0; c < 4; ++c) img.rgba[4 * i + size_t(c)] = w > 0.0f ? img.rgba[4 * i + size_t(c)] / w : 0.0f;
    }
  } else if (const Pass divisor = divisor_of(pass)) {
    const Image& color = find(divisor);
    for (size_t i = 0; i + 2 < img.rgba.size(); i += 3) {
      const Vec3 q = divide_even_color(Vec3(img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]),
                                       Vec3(color.rgba[i], color.rgba[i + 1], color.rgba[i + 2]));
      img.rgba[i] = q.x;
      img.rgba[i + 1] = q.y;
      img.rgba[i + 2] = q.z;
    }
  }
  return img;
}

}  // namespace torrance
