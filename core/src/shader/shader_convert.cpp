// Blender's converter nodes as Cycles 3.4 evaluates them (see shader_convert.h). The expressions
// keep Cycles' order of operations, so single-precision results match its kernel's to the
// rounding of the last operation.
#include "torrance/shader/shader_convert.h"

#include "torrance/util/smoothstep.h"

#include <cmath>
#include <iterator>

namespace torrance::shader {

namespace {

// Cycles' scalar min/max: the comparison picks, so max(NaN, 0) is 0 and a clamp sends NaN low.
inline float pick_max(float a, float b) { return a > b ? a : b; }
inline float pick_min(float a, float b) { return a < b ? a : b; }
inline float clamp_to(float v, float lo, float hi) { return pick_min(pick_max(v, lo), hi); }
inline float saturate(float v) { return clamp_to(v, 0.0f, 1.0f); }
inline float safe_divide(float a, float b) { return b != 0.0f ? a / b : 0.0f; }

glm::vec4 table_entry(const float* table, int stride, int i) {
  // A colour ramp's RGBA entries (the common case) as one load instead of a loop of four.
  if (stride == 4) return glm::vec4(table[4 * i], table[4 * i + 1], table[4 * i + 2], table[4 * i + 3]);
  glm::vec4 e(0.0f);
  for (int k = 0; k < stride; ++k) e[k] = table[i * stride + k];
  return e;
}

// The smoother step (6t^5 - 15t^4 + 10t^3) of t = (x - e0) / (e1 - e0) within [0, 1].
float smoother_step(float e0, float e1, float x) {
  const float t = saturate(safe_divide(x - e0, e1 - e0));
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

float stepped(float factor, float steps) { return steps > 0.0f ? std::floor(factor * (steps + 1.0f)) / steps : 0.0f; }

float map_range_factor(MapRangeMode mode, float value, float from_min, float from_max) {
  switch (mode) {
    case MapRangeMode::Stepped:
      return (value - from_min) / (from_max - from_min);  // stepped by the caller
    case MapRangeMode::SmoothStep:
      return from_min > from_max ? 1.0f - smooth_step(from_max, from_min, value)
                                 : smooth_step(from_min, from_max, value);
    case MapRangeMode::SmootherStep:
      return from_min > from_max ? 1.0f - smoother_step(from_max, from_min, value)
                                 : smoother_step(from_min, from_max, value);
    case MapRangeMode::Linear:
    default:
      return (value - from_min) / (from_max - from_min);
  }
}

// Blackbody: Cycles 3.4's fit to the colour of a black body in Rec. 709 (svm/math_util.h, the
// coefficients from kernel/tables.h), one segment per temperature range from `from` kelvin on:
// red = r0 / T + r1 T + r2, green = g0 / T + g1 T + g2, blue = ((b0 T + b1) T + b2) T + b3.
struct BlackbodySegment {
  float from;
  float r[3], g[3], b[4];
};
constexpr BlackbodySegment kBlackbodyFit[] = {
    {800.0f,
     {1.61919106e+03f, -2.05010916e-03f, 5.02995757e+00f},
     {-4.88999748e+02f, 6.04330754e-04f, -7.55807526e-02f},
     {5.96945309e-11f, -4.85742887e-08f, -9.70622247e-05f, -4.07936148e-03f}},
    {965.0f,
     {2.48845471e+03f, -1.11330907e-03f, 3.22621544e+00f},
     {-7.55994277e+02f, 3.16730098e-04f, 4.78306139e-01f},
     {2.40430366e-11f, 5.55021075e-08f, -1.98503712e-04f, 2.89312858e-02f}},
    {1167.0f,
     {3.34143193e+03f, -4.86551192e-04f, 1.76486769e+00f},
     {-1.02363977e+03f, 1.20223470e-04f, 9.36662319e-01f},
     {-1.40949732e-11f, 1.89878968e-07f, -3.56632824e-04f, 9.10767778e-02f}},
    {1449.0f,
     {4.09461742e+03f, -1.27446582e-04f, 7.25731635e-01f},
     {-1.26571316e+03f, 4.87340896e-06f, 1.27054498e+00f},
     {-3.61460868e-11f, 2.84822009e-07f, -4.93211319e-04f, 1.56723440e-01f}},
    {1902.0f,
     {4.67028036e+03f, 2.91258199e-05f, 1.26703442e-01f},
     {-1.42529332e+03f, -4.01150431e-05f, 1.43972784e+00f},
     {-1.97075738e-11f, 1.75359352e-07f, -2.50542825e-04f, -2.22783266e-02f}},
    {3315.0f,
     {4.59509185e+03f, 2.87495649e-05f, 1.50345020e-01f},
     {-1.17554822e+03f, -2.16378048e-05f, 1.30408023e+00f},
     {-1.61997957e-13f, -1.64216008e-08f, 3.86216271e-04f, -7.38077418e-01f}},
    {6365.0f,
     {3.78717450e+03f, 9.35907826e-06f, 3.99075871e-01f},
     {-5.00799571e+02f, -4.59832026e-06f, 1.09098763e+00f},
     {6.72650283e-13f, -2.73078809e-08f, 4.24098264e-04f, -7.52335691e-01f}},
};
constexpr float kBlackbodyMin = 800.0f, kBlackbodyMax = 12000.0f;
// The fit's values below 800 K and from 12000 K on.
const Vec3 kBlackbodyCold(5.413294490189271f, -0.20319390035873933f, -0.0822535242887164f);
const Vec3 kBlackbodyHot(0.8262954810464208f, 0.9945080501520986f, 1.566307710274283f);

// The CIE 1931 2-degree colour-matching functions x, y, z every 5 nm from 380 to 780 nm, to four
// decimals (the table Cycles 3.4 interpolates, kernel/tables.h).
constexpr int kCieSteps = 80;  // intervals
constexpr float kCieFirst = 380.0f, kCieStep = 5.0f;
constexpr float kCie1931[kCieSteps + 1][3] = {
    {0.0014f, 0.0000f, 0.0065f}, {0.0022f, 0.0001f, 0.0105f}, {0.0042f, 0.0001f, 0.0201f},  // 380-390
    {0.0076f, 0.0002f, 0.0362f}, {0.0143f, 0.0004f, 0.0679f}, {0.0232f, 0.0006f, 0.1102f},  // 395-405
    {0.0435f, 0.0012f, 0.2074f}, {0.0776f, 0.0022f, 0.3713f}, {0.1344f, 0.0040f, 0.6456f},  // 410-420
    {0.2148f, 0.0073f, 1.0391f}, {0.2839f, 0.0116f, 1.3856f}, {0.3285f, 0.0168f, 1.6230f},  // 425-435
    {0.3483f, 0.0230f, 1.7471f}, {0.3481f, 0.0298f, 1.7826f}, {0.3362f, 0.0380f, 1.7721f},  // 440-450
    {0.3187f, 0.0480f, 1.7441f}, {0.2908f, 0.0600f, 1.6692f}, {0.2511f, 0.0739f, 1.5281f},  // 455-465
    {0.1954f, 0.0910f, 1.2876f}, {0.1421f, 0.1126f, 1.0419f}, {0.0956f, 0.1390f, 0.8130f},  // 470-480
    {0.0580f, 0.1693f, 0.6162f}, {0.0320f, 0.2080f, 0.4652f}, {0.0147f, 0.2586f, 0.3533f},  // 485-495
    {0.0049f, 0.3230f, 0.2720f}, {0.0024f, 0.4073f, 0.2123f}, {0.0093f, 0.5030f, 0.1582f},  // 500-510
    {0.0291f, 0.6082f, 0.1117f}, {0.0633f, 0.7100f, 0.0782f}, {0.1096f, 0.7932f, 0.0573f},  // 515-525
    {0.1655f, 0.8620f, 0.0422f}, {0.2257f, 0.9149f, 0.0298f}, {0.2904f, 0.9540f, 0.0203f},  // 530-540
    {0.3597f, 0.9803f, 0.0134f}, {0.4334f, 0.9950f, 0.0087f}, {0.5121f, 1.0000f, 0.0057f},  // 545-555
    {0.5945f, 0.9950f, 0.0039f}, {0.6784f, 0.9786f, 0.0027f}, {0.7621f, 0.9520f, 0.0021f},  // 560-570
    {0.8425f, 0.9154f, 0.0018f}, {0.9163f, 0.8700f, 0.0017f}, {0.9786f, 0.8163f, 0.0014f},  // 575-585
    {1.0263f, 0.7570f, 0.0011f}, {1.0567f, 0.6949f, 0.0010f}, {1.0622f, 0.6310f, 0.0008f},  // 590-600
    {1.0456f, 0.5668f, 0.0006f}, {1.0026f, 0.5030f, 0.0003f}, {0.9384f, 0.4412f, 0.0002f},  // 605-615
    {0.8544f, 0.3810f, 0.0002f}, {0.7514f, 0.3210f, 0.0001f}, {0.6424f, 0.2650f, 0.0000f},  // 620-630
    {0.5419f, 0.2170f, 0.0000f}, {0.4479f, 0.1750f, 0.0000f}, {0.3608f, 0.1382f, 0.0000f},  // 635-645
    {0.2835f, 0.1070f, 0.0000f}, {0.2187f, 0.0816f, 0.0000f}, {0.1649f, 0.0610f, 0.0000f},  // 650-660
    {0.1212f, 0.0446f, 0.0000f}, {0.0874f, 0.0320f, 0.0000f}, {0.0636f, 0.0232f, 0.0000f},  // 665-675
    {0.0468f, 0.0170f, 0.0000f}, {0.0329f, 0.0119f, 0.0000f}, {0.0227f, 0.0082f, 0.0000f},  // 680-690
    {0.0158f, 0.0057f, 0.0000f}, {0.0114f, 0.0041f, 0.0000f}, {0.0081f, 0.0029f, 0.0000f},  // 695-705
    {0.0058f, 0.0021f, 0.0000f}, {0.0041f, 0.0015f, 0.0000f}, {0.0029f, 0.0010f, 0.0000f},  // 710-720
    {0.0020f, 0.0007f, 0.0000f}, {0.0014f, 0.0005f, 0.0000f}, {0.0010f, 0.0004f, 0.0000f},  // 725-735
    {0.0007f, 0.0002f, 0.0000f}, {0.0005f, 0.0002f, 0.0000f}, {0.0003f, 0.0001f, 0.0000f},  // 740-750
    {0.0002f, 0.0001f, 0.0000f}, {0.0002f, 0.0001f, 0.0000f}, {0.0001f, 0.0000f, 0.0000f},  // 755-765
    {0.0001f, 0.0000f, 0.0000f}, {0.0001f, 0.0000f, 0.0000f}, {0.0000f, 0.0000f, 0.0000f},  // 770-780
};

// CIE XYZ (D65) -> scene linear Rec. 709, rows: the inverse of the sRGB primaries' RGB -> XYZ
// matrix of Blender's colour management (datafiles/colormanagement/luts/srgb_to_xyz.spimtx),
// which is what Cycles 3.4 derives from the default config's aces_interchange role (to ~1e-6).
constexpr float kXyzToRec709[3][3] = {
    {3.2404548360f, -1.5371388501f, -0.4985315469f},
    {-0.9692663899f, 1.8760109288f, 0.0415560823f},
    {0.0556434196f, -0.2040258543f, 1.0572251625f},
};
// Cycles' empirical scale that keeps Wavelength's channels at most 1.
constexpr float kWavelengthScale = 1.0f / 2.52f;

}  // namespace

glm::vec4 ramp_lookup(const float* table, int entries, int stride, float f, bool interpolate, bool extrapolate) {
  if (entries < 1 || stride < 1 || stride > 4) return glm::vec4(0.0f);
  const float last = float(entries - 1);
  if (extrapolate && entries >= 2 && (f < 0.0f || f > 1.0f)) {
    // The line through the two end entries, continued by how far f lies beyond the end.
    const bool below = f < 0.0f;
    const glm::vec4 end = table_entry(table, stride, below ? 0 : entries - 1);
    const glm::vec4 slope = end - table_entry(table, stride, below ? 1 : entries - 2);
    const float beyond = below ? -f : f - 1.0f;
    return end + slope * beyond * last;
  }
  const float x = saturate(f) * last;
  int i = int(x);
  i = i < 0 ? 0 : (i > entries - 1 ? entries - 1 : i);
  const float t = x - float(i);
  glm::vec4 a = table_entry(table, stride, i);
  if (interpolate && t > 0.0f) a = (1.0f - t) * a + t * table_entry(table, stride, i + 1);
  return a;
}

glm::vec4 color_ramp(const float* table, int size, float fac, bool interpolate) {
  return ramp_lookup(table, size / 4, 4, fac, interpolate, false);
}

Vec3 curves(const float* table, int size, float fac, const Vec3& c, bool extrapolate) {
  if (size < 2) return (1.0f - fac) * c;
  const float min_x = table[0], range = table[1] - table[0];
  const Vec3 relative = (c - Vec3(min_x)) / range;
  const int entries = (size - 2) / 3;
  const Vec3 mapped(ramp_lookup(table + 2, entries, 3, relative.x, true, extrapolate).x,
                    ramp_lookup(table + 2, entries, 3, relative.y, true, extrapolate).y,
                    ramp_lookup(table + 2, entries, 3, relative.z, true, extrapolate).z);
  return (1.0f - fac) * c + fac * mapped;
}

float float_curve(const float* table, int size, float fac, float value, bool extrapolate) {
  if (size < 2) return (1.0f - fac) * value;
  const float relative = (value - table[0]) / (table[1] - table[0]);
  const float mapped = ramp_lookup(table + 2, size - 2, 1, relative, true, extrapolate).x;
  return (1.0f - fac) * value + fac * mapped;
}

float map_range(MapRangeMode mode, float value, float from_min, float from_max, float to_min, float to_max,
                float steps, bool clamp_result) {
  float result = 0.0f;
  if (from_max != from_min) {
    float factor = map_range_factor(mode, value, from_min, from_max);
    if (mode == MapRangeMode::Stepped) factor = stepped(factor, steps);
    result = to_min + factor * (to_max - to_min);
  }
  return clamp_result ? clamp(ClampMode::Range, result, to_min, to_max) : result;
}

Vec3 vector_map_range(MapRangeMode mode, const Vec3& value, const Vec3& from_min, const Vec3& from_max,
                      const Vec3& to_min, const Vec3& to_max, const Vec3& steps, bool clamp_result) {
  Vec3 factor(0.0f);
  for (int k = 0; k < 3; ++k) factor[k] = safe_divide(value[k] - from_min[k], from_max[k] - from_min[k]);
  switch (mode) {
    case MapRangeMode::Stepped:
      for (int k = 0; k < 3; ++k) factor[k] = stepped(factor[k], steps[k]);
      break;
    case MapRangeMode::SmoothStep:
      for (int k = 0; k < 3; ++k) factor[k] = smooth_step(0.0f, 1.0f, saturate(factor[k]));
      break;
    case MapRangeMode::SmootherStep:
      for (int k = 0; k < 3; ++k) {
        const float t = saturate(factor[k]);
        factor[k] = t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
      }
      break;
    case MapRangeMode::Linear:
    default:
      break;
  }
  Vec3 result = to_min + factor * (to_max - to_min);
  if (clamp_result && (mode == MapRangeMode::Linear || mode == MapRangeMode::Stepped))
    for (int k = 0; k < 3; ++k) result[k] = clamp(ClampMode::Range, result[k], to_min[k], to_max[k]);
  return result;
}

float clamp(ClampMode mode, float value, float min, float max) {
  if (mode == ClampMode::Range && min > max) return clamp_to(value, max, min);
  return clamp_to(value, min, max);
}

Vec3 blackbody(float kelvin) {
  Vec3 rgb;
  if (kelvin >= kBlackbodyMax) {
    rgb = kBlackbodyHot;
  } else if (kelvin < kBlackbodyMin) {
    rgb = kBlackbodyCold;
  } else {
    int s = int(std::size(kBlackbodyFit)) - 1;
    while (s > 0 && !(kelvin >= kBlackbodyFit[s].from)) --s;  // NaN: the first segment
    const BlackbodySegment& f = kBlackbodyFit[s];
    const float inverse = 1.0f / kelvin;
    rgb = Vec3(f.r[0] * inverse + f.r[1] * kelvin + f.r[2], f.g[0] * inverse + f.g[1] * kelvin + f.g[2],
               ((f.b[0] * kelvin + f.b[1]) * kelvin + f.b[2]) * kelvin + f.b[3]);
  }
  return Vec3(pick_max(rgb.x, 0.0f), pick_max(rgb.y, 0.0f), pick_max(rgb.z, 0.0f));
}

Vec3 xyz_to_rec709(const Vec3& xyz) {
  Vec3 rgb;
  for (int k = 0; k < 3; ++k)
    rgb[k] = kXyzToRec709[k][0] * xyz.x + kXyzToRec709[k][1] * xyz.y + kXyzToRec709[k][2] * xyz.z;
  return rgb;
}

Vec3 cie_1931(float nanometres) {
  // The table index, truncated toward 0 (so -1 < index < 0 reads the first interval).
  const float index = (nanometres - kCieFirst) * (1.0f / kCieStep);
  Vec3 xyz(0.0f);
  if (index > -1.0f && index < float(kCieSteps)) {
    const int i = int(index);
    const float t = index - float(i);
    const Vec3 a(kCie1931[i][0], kCie1931[i][1], kCie1931[i][2]);
    const Vec3 b(kCie1931[i + 1][0], kCie1931[i + 1][1], kCie1931[i + 1][2]);
    xyz = a + t * (b - a);
  }
  return xyz;
}

Vec3 wavelength(float nanometres) {
  const Vec3 rgb = xyz_to_rec709(cie_1931(nanometres)) * kWavelengthScale;
  return Vec3(pick_max(rgb.x, 0.0f), pick_max(rgb.y, 0.0f), pick_max(rgb.z, 0.0f));
}

// ---- the ops ---------------------------------------------------------------------------------

OpValue color_ramp_op(const ShaderOpContext& c) {
  return color_ramp(c.data, c.data_size, c.value(0), c.ins.flags & 1);
}

OpValue rgb_curves_op(const ShaderOpContext& c) {
  return glm::vec4(curves(c.data, c.data_size, c.value(0), c.vector(1), c.ins.flags & 1), 1.0f);
}

OpValue vector_curves_op(const ShaderOpContext& c) {
  return glm::vec4(curves(c.data, c.data_size, c.value(0), c.vector(1), c.ins.flags & 1), 0.0f);
}

OpValue float_curve_op(const ShaderOpContext& c) {
  return glm::vec4(float_curve(c.data, c.data_size, c.value(0), c.value(1), c.ins.flags & 1), 0.0f, 0.0f, 0.0f);
}

OpValue map_range_op(const ShaderOpContext& c) {
  const float v = map_range(MapRangeMode(c.ins.mode), c.value(0), c.value(1), c.value(2), c.value(3), c.value(4),
                            c.value(5), c.ins.flags & 1);
  return glm::vec4(v, 0.0f, 0.0f, 0.0f);
}

OpValue vector_map_range_op(const ShaderOpContext& c) {
  return glm::vec4(vector_map_range(MapRangeMode(c.ins.mode), c.vector(0), c.vector(1), c.vector(2), c.vector(3),
                                    c.vector(4), c.vector(5), c.ins.flags & 1),
                   0.0f);
}

OpValue clamp_op(const ShaderOpContext& c) {
  return glm::vec4(clamp(ClampMode(c.ins.mode), c.value(0), c.value(1), c.value(2)), 0.0f, 0.0f, 0.0f);
}

OpValue blackbody_op(const ShaderOpContext& c) { return glm::vec4(blackbody(c.value(0)), 1.0f); }

OpValue wavelength_op(const ShaderOpContext& c) { return glm::vec4(wavelength(c.value(0)), 1.0f); }

}  // namespace torrance::shader
