// The table Cycles 4.x/5.x's microfiber sheen reads (sheen_bsdf.h): three 32 x 32 planes (the LTC
// coefficients a and b, the albedo R), row = roughness, column = cos theta of the viewer, grid
// point k at k / 31. The values are Cycles' own (its table_sheen_ltc, the fit of Zeltner et al.
// 2022, Apache-2.0), read out of Blender 4.2's and 5.3's Cycles (identical there); they are the
// fitted data the model is, not something Torrance can recompute.
#pragma once

namespace torrance::sheen_ltc {

inline constexpr int kSize = 32;

struct Coefficients {
  float a, b, albedo;
};
// Cycles' lookup: bilinear in (cos_o, roughness), each clamped to [0, 1].
Coefficients lookup(float cos_o, float roughness);

}  // namespace torrance::sheen_ltc
