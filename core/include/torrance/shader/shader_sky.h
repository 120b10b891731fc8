// The Sky Texture node (opcode 61 of the texture family) as Cycles 3.4-5.x renders it (svm/sky.h
// and the sky model Cycles precomputes on the host):
//   TexSky (61)  in0 Vector (the direction; not normalised, as Cycles); mode: SkyModel; a table:
//     Preetham: sun phi, sun theta, zenith x, y, Y (Cycles' radiance_x/y/z: Y, x, y), then the
//       five Perez coefficients of Y, of x and of y (kPreethamTable floats)
//     Nishita:  sun disc XYZ at its bottom and top, sun elevation, sun rotation (Cycles' wrapped
//       2 pi - rotation), angular diameter (-1: no disc), sun intensity, width, height, then the
//       sky texture's XYZ texels, row by row from the horizon up (kNishitaHeader + 3 w h floats)
//     Hosek / Wilkie: kHosekTable floats (below)
//     Scattering (Blender 5.x's Single and Multiple Scattering, one kernel): sun disc XYZ at its
//       bottom and top, sun elevation, rotation (wrapped as Nishita's), angular diameter (-1: no
//       disc), sun intensity, the elevation below which the Earth hides the disc (negative),
//       width, height, then the texels row by row from the nadir up (kScatteringHeader + 3 w h)
// The add-on fills the tables with the functions below (through the Python module), as Cycles'
// SkyTextureNode::compile does; the op writes the Color (r, g, b, 1) in scene linear Rec. 709.
#pragma once

#include "torrance/shader/shader_program.h"

#include <vector>

namespace torrance::shader {

enum class SkyModel : uint8_t { Preetham, Nishita, Scattering, Hosek };
constexpr int kSkyModels = int(SkyModel::Hosek) + 1;
// Hosek / Wilkie's table: sun phi, theta, the radiance scale of X, Y, Z, then their nine
// parameters each (Cycles' SVMNodeTexSkyPreethamData as Hosek fills it).
constexpr int kHosekTable = 32;
constexpr int kPreethamTable = 20;
constexpr int kNishitaHeader = 12;
// Cycles' precomputed Nishita texture: 512 x 128 texels (longitude x elevation).
constexpr int kNishitaWidth = 512, kNishitaHeight = 128;
constexpr int kScatteringHeader = 13;
// Cycles 5.x's sky texture: 512 x 256 texels, the whole sphere.
constexpr int kScatteringWidth = 512, kScatteringHeight = 256;

// ---- host-side precomputation (what Cycles' SkyTextureNode::compile computes) -------------------

// Preetham's table for a sun direction (unit, z up) and turbidity: the zenith's xyY and the
// Perez coefficients of Preetham, Shirley and Smits' fits, the zenith values divided by the
// Perez function at the zenith, as Cycles does.
std::vector<float> preetham_table(const Vec3& sun_direction, float turbidity);

// The Nishita model's atmosphere: single scattering of sunlight by air (Rayleigh), dust (Mie) and
// absorption by ozone, 21 wavelengths 380..780 nm, integrated along each view ray in 32 segments
// and toward the sun by 8-point Gauss-Laguerre quadrature (Blender's intern/sky), from
// `altitude` metres above a 6360 km Earth under a 60 km atmosphere.
struct NishitaSky {
  float sun_elevation = 0.2618f;  // radians
  float sun_rotation = 0.0f;      // radians, about z
  float sun_size = 0.009512f;     // the disc's angular diameter, radians (Cycles: at least 0.0005)
  float sun_intensity = 1.0f;
  bool sun_disc = true;
  float altitude = 1.0f;  // metres (Cycles clamps to [1, 59999])
  float air = 1.0f, dust = 1.0f, ozone = 1.0f;  // density scales
  // Cycles 3.6+ first wraps the elevation into [-pi/2, pi/2], turning the sun about z by pi where
  // it passes the zenith or nadir (3.4 takes any elevation as it is).
  bool wrap_elevation = false;
};
// The table of the op (header and the kNishitaWidth x kNishitaHeight texels), as Cycles computes
// it (clamps included).
std::vector<float> nishita_table(const NishitaSky& sky);

// Cycles' sun position fix-up (3.6+): the elevation wrapped into [-pi/2, pi/2], the sun turned
// about z by pi where it passes the zenith or nadir. Returns (elevation, rotation).
Vec2 wrapped_sun(float elevation, float rotation);
// The rotation as Cycles' kernel takes it: 2 pi - (rotation wrapped into [0, 2 pi)).
float cycles_sun_rotation(float rotation);

// Hosek / Wilkie's table for a sun direction (unit, z up), turbidity and ground albedo, cooked
// from the published XYZ dataset as Cycles does (shader_sky_hosek.cpp).
std::vector<float> hosek_table(const Vec3& sun_direction, float turbidity, float ground_albedo);

// Blender 5.x's scattering skies. Single Scattering: the Nishita atmosphere above, its texture
// now over the whole sphere (black below the horizon); Multiple Scattering: Fernando Garcia
// Linan's spectral model (4 wavelengths, a transmittance table, a fitted multiple-scattering
// term and the ground's bounce) in a 6371 km Earth under 100 km of atmosphere.
struct ScatteringSky {
  bool multiple = true;
  float sun_elevation = 0.2618f;  // radians
  float sun_rotation = 0.0f;      // radians, about z
  float sun_size = 0.009512f;     // the disc's angular diameter, radians (Cycles: at least 0.0005)
  float sun_intensity = 1.0f;
  bool sun_disc = true;
  float altitude = 100.0f;  // metres
  float air = 1.0f, aerosol = 1.0f, ozone = 1.0f;  // density scales
};
std::vector<float> scattering_table(const ScatteringSky& sky);

// The texels (kScatteringWidth x kScatteringHeight XYZ) and the sun disc's XYZ at its bottom and
// top (6 floats) of each model: shader_sky_nishita.cpp and shader_sky_multiple.cpp.
void single_scattering_texture(float* texels, float sun_elevation, float altitude, float air, float aerosol,
                               float ozone);
void single_scattering_sun(float* bottom_top, float sun_elevation, float size, float altitude, float air,
                           float aerosol);
void multiple_scattering_texture(float* texels, float sun_elevation, float altitude, float air, float aerosol,
                                 float ozone);
void multiple_scattering_sun(float* bottom_top, float sun_elevation, float size, float altitude, float air,
                             float aerosol, float ozone);

// ---- evaluation --------------------------------------------------------------------------------

// CIE XYZ -> the scene's linear Rec. 709, negative channels clamped (Cycles' xyz_to_rgb_clamped).
Vec3 xyz_to_rec709_clamped(const Vec3& xyz);

Vec3 sky_preetham(const Vec3& dir, const float* table);
// table/size: the Nishita table (size its length); an inconsistent table gives black.
Vec3 sky_nishita(const Vec3& dir, const float* table, int size);
Vec3 sky_hosek(const Vec3& dir, const float* table);
// table/size: the Scattering table; an inconsistent table gives black.
Vec3 sky_scattering(const Vec3& dir, const float* table, int size);

OpValue sky_op(const ShaderOpContext& c);

}  // namespace torrance::shader
